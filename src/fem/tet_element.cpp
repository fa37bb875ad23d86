#include "fem/tet_element.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {

double tet_volume(const TetCorners& p) {
  return (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0;
}

Mat34 tet_shape_gradients(const TetCorners& p, double* volume) {
  Mat3 edges;
  edges << p[1] - p[0], p[2] - p[0], p[3] - p[0];
  const double det = edges.determinant();
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) throw NumericError("tet_shape_gradients: degenerate tet");
  // Rows of Dm^-1 are the gradients of N_1..N_3; N_0 = 1 - N_1 - N_2 - N_3.
  const Mat3 inv = edges.inverse();
  Mat34 g;
  g.col(1) = inv.row(0).transpose();
  g.col(2) = inv.row(1).transpose();
  g.col(3) = inv.row(2).transpose();
  g.col(0) = -(g.col(1) + g.col(2) + g.col(3));
  if (volume != nullptr) *volume = det / 6.0;
  return g;
}

Mat4 tet_diffusion_stiffness(const Mat34& grads, double volume, double k) {
  return (k * volume) * (grads.transpose() * grads);
}

Mat4 tet_consistent_mass(double volume, double c) {
  Mat4 m = Mat4::Constant(c * volume / 20.0);
  m.diagonal().array() *= 2.0;
  return m;
}

Vec4 tet_lumped_mass(double volume, double c) {
  return Vec4::Constant(c * volume / 4.0);
}

Mat3 triangle_robin_matrix(const Vec3& a, const Vec3& b, const Vec3& c, double h) {
  Mat3 m = Mat3::Constant(h * triangle_area(a, b, c) / 12.0);
  m.diagonal().array() *= 2.0;
  return m;
}

Vec3 triangle_robin_load(const Vec3& a, const Vec3& b, const Vec3& c, double h, double ambient) {
  return Vec3::Constant(h * ambient * triangle_area(a, b, c) / 3.0);
}

Vec2 lame_parameters(double youngs_modulus, double poisson_ratio) {
  const double e = youngs_modulus;
  const double nu = poisson_ratio;
  return Vec2(e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu)));
}

Mat6 isotropic_elasticity(double youngs_modulus, double poisson_ratio) {
  const Vec2 lame = lame_parameters(youngs_modulus, poisson_ratio);
  const double lambda = lame[0];
  const double mu = lame[1];
  Mat6 c = Mat6::Zero();
  c.topLeftCorner<3, 3>().setConstant(lambda);
  c.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  c.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  return c;
}

Mat6x12 tet_strain_matrix(const Mat34& grads) {
  Mat6x12 b = Mat6x12::Zero();
  for (int i = 0; i < 4; ++i) {
    const double bx = grads(0, i);
    const double by = grads(1, i);
    const double bz = grads(2, i);
    const int c = 3 * i;
    b(0, c) = bx;
    b(1, c + 1) = by;
    b(2, c + 2) = bz;
    b(3, c) = by;
    b(3, c + 1) = bx;
    b(4, c + 1) = bz;
    b(4, c + 2) = by;
    b(5, c) = bz;
    b(5, c + 2) = bx;
  }
  return b;
}

Mat12 tet_linear_stiffness(const Mat34& grads, double volume, double youngs_modulus, double poisson_ratio) {
  const Mat6x12 b = tet_strain_matrix(grads);
  const Mat12 k = volume * (b.transpose() * isotropic_elasticity(youngs_modulus, poisson_ratio) * b);
  return 0.5 * (k + k.transpose());
}

Mat3 tet_rest_edge_inverse(const TetCorners& rest) {
  Mat3 edges;
  edges << rest[1] - rest[0], rest[2] - rest[0], rest[3] - rest[0];
  const double det = edges.determinant();
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) throw NumericError("tet_rest_edge_inverse: degenerate tet");
  return edges.inverse();
}

Mat3 tet_deformation_gradient(const TetCorners& x, const Mat3& rest_edge_inverse) {
  Mat3 ds;
  ds << x[1] - x[0], x[2] - x[0], x[3] - x[0];
  return ds * rest_edge_inverse;
}

Mat3 rotation_from_deformation(const Mat3& deformation_gradient) {
  const Eigen::JacobiSVD<Mat3> svd(deformation_gradient, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  const Mat3 v = svd.matrixV();
  if ((u * v.transpose()).determinant() < 0.0) u.col(2) = -u.col(2);  // singular values sorted: col 2 smallest
  return u * v.transpose();
}

namespace {

// Packets of Eigen's SIMD layer (SSE2: 2 doubles; AVX: 4), four per group of lanes in batches; a lone matrix
// runs the same arithmetic on plain doubles (Eigen's scalar packet operations).
using Packet = Eigen::internal::packet_traits<double>::type;
constexpr std::size_t packet_size = static_cast<std::size_t>(Eigen::internal::packet_traits<double>::size);
constexpr std::size_t batch_lanes = 4 * packet_size;

template <typename P, std::size_t Width, std::size_t Lanes>
void polar_lane_group(const Mat3* f, Mat3* r, std::size_t count) {
  using namespace Eigen::internal;
  alignas(64) double x[9][Lanes];
  alignas(64) double flags[3][Lanes];  // all-ones bit masks: 0 scaled, 1 open (iterating), 2 failed
  const double all_ones = Eigen::numext::bit_cast<double>(~std::uint64_t{0});
  for (std::size_t l = 0; l < Lanes; ++l) {
    const Mat3& m = l < count ? f[l] : f[0];
    for (int k = 0; k < 9; ++k) x[k][l] = m(k);
    flags[0][l] = all_ones;
    flags[1][l] = l < count ? all_ones : 0.0;
    flags[2][l] = 0.0;
  }
  const P zero = pset1<P>(0.0), one = pset1<P>(1.0), half = pset1<P>(0.5);
  const P largest = pset1<P>(std::numeric_limits<double>::max());
  const P settled = pset1<P>(1e-8), rescale = pset1<P>(1e-2);
  for (int iteration = 0; iteration < 30; ++iteration) {
    bool any_open = false;
    for (std::size_t j = 0; j < Lanes; j += Width) {
      P v[9];
      for (int k = 0; k < 9; ++k) v[k] = pload<P>(&x[k][j]);
      // X^-T = cofactor(X) / det X; cofactor columns x1 x x2, x2 x x0, x0 x x1.
      auto cross = [](const P& a0, const P& a1, const P& b0, const P& b1) { return psub(pmul(a0, b1), pmul(a1, b0)); };
      const P k[9] = {cross(v[4], v[5], v[7], v[8]), cross(v[5], v[3], v[8], v[6]), cross(v[3], v[4], v[6], v[7]),
                      cross(v[7], v[8], v[1], v[2]), cross(v[8], v[6], v[2], v[0]), cross(v[6], v[7], v[0], v[1]),
                      cross(v[1], v[2], v[4], v[5]), cross(v[2], v[0], v[5], v[3]), cross(v[0], v[1], v[3], v[4])};
      const P det = padd(padd(pmul(v[0], k[0]), pmul(v[1], k[1])), pmul(v[2], k[2]));
      P cof_norm = pmul(k[0], k[0]), x_norm = pmul(v[0], v[0]);
      for (int e = 1; e < 9; ++e) {
        cof_norm = padd(cof_norm, pmul(k[e], k[e]));
        x_norm = padd(x_norm, pmul(v[e], v[e]));
      }
      // Inverted, degenerate or not finite: the SVD decides (det <= DBL_MAX is false for inf and NaN).
      const P ok = pand(pcmp_lt(zero, det), pcmp_le(det, largest));
      const P scaled = pload<P>(&flags[0][j]);
      const P open = pload<P>(&flags[1][j]);
      const P zeta = pselect(scaled, psqrt(psqrt(pdiv(cof_norm, pmul(pmul(det, det), x_norm)))), one);
      const P inverse = pdiv(one, pmul(zeta, det));
      const P step = pand(open, ok);
      P change = zero;
      for (int e = 0; e < 9; ++e) {
        const P next = pmul(half, padd(pmul(zeta, v[e]), pmul(k[e], inverse)));
        change = pmax(change, pabs(psub(next, v[e])));
        pstore(&x[e][j], pselect(step, next, v[e]));
      }
      const P still_open = pandnot(step, pcmp_lt(change, settled));
      pstore(&flags[0][j], pselect(step, pcmp_lt(rescale, change), scaled));
      pstore(&flags[1][j], still_open);
      pstore(&flags[2][j], por(pload<P>(&flags[2][j]), pandnot(open, ok)));
      any_open = any_open || predux_any(still_open);
    }
    if (!any_open) break;
  }
  for (std::size_t l = 0; l < count; ++l) {
    const bool failed = Eigen::numext::bit_cast<std::uint64_t>(flags[2][l]) != 0 ||
                        Eigen::numext::bit_cast<std::uint64_t>(flags[1][l]) != 0;
    if (failed) {
      r[l] = rotation_from_deformation(f[l]);
    } else {
      for (int k = 0; k < 9; ++k) r[l](k) = x[k][l];
    }
  }
}

}  // namespace

Mat3 polar_rotation(const Mat3& deformation_gradient) {
  Mat3 r;
  polar_lane_group<double, 1, 1>(&deformation_gradient, &r, 1);
  return r;
}

void polar_rotations(const Mat3* deformation_gradients, Mat3* rotations, std::size_t count) {
  for (std::size_t i = 0; i < count; i += batch_lanes)
    polar_lane_group<Packet, packet_size, batch_lanes>(deformation_gradients + i, rotations + i,
                                                       std::min(batch_lanes, count - i));
}

Vec12 rotate_blocks(const Mat3& r, const Vec12& v) {
  Vec12 out;
  for (int i = 0; i < 4; ++i) out.segment<3>(3 * i) = r * v.segment<3>(3 * i);
  return out;
}

Mat12 rotate_stiffness(const Mat3& r, const Mat12& k) {
  Mat12 out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) out.block<3, 3>(3 * i, 3 * j) = r * k.block<3, 3>(3 * i, 3 * j) * r.transpose();
  }
  return out;
}

Vec12 tet_eigenstrain_force(const Mat34& grads, double volume, const Mat6& elasticity, double s) {
  Eigen::Matrix<double, 6, 1> eps0 = Eigen::Matrix<double, 6, 1>::Zero();
  eps0.head<3>().setConstant(s);
  return volume * (tet_strain_matrix(grads).transpose() * (elasticity * eps0));
}

Vec12 tet_corotational_force(const Mat12& k, const Mat3& r, const Vec12& x, const Vec12& x0, const Vec12& f_eig) {
  const Vec12 unrotated = rotate_blocks(r.transpose(), x) - x0;
  return -rotate_blocks(r, k * unrotated - f_eig);
}

double tet_corotational_energy(const TetCorners& x, const Mat3& rest_edge_inverse, double volume,
                               const Mat6& elasticity, double s) {
  const Mat3 f = tet_deformation_gradient(x, rest_edge_inverse);
  const Mat3 r = rotation_from_deformation(f);
  const Mat3 e = 0.5 * (r.transpose() * f + f.transpose() * r) - Mat3::Identity();
  Eigen::Matrix<double, 6, 1> eps;
  eps << e(0, 0) - s, e(1, 1) - s, e(2, 2) - s, 2.0 * e(0, 1), 2.0 * e(1, 2), 2.0 * e(2, 0);
  return 0.5 * volume * eps.dot(elasticity * eps);
}

double tet_volume_barrier(const Mat3& deformation_gradient, double s, double kappa, double r0, Mat3* gradient) {
  if (gradient != nullptr) gradient->setZero();
  if (!(r0 > 0.0) || !(kappa > 0.0)) return 0.0;
  const double target = (1.0 + s) * (1.0 + s) * (1.0 + s);
  const Mat3& f = deformation_gradient;
  const double r = f.determinant() / target;
  if (r >= r0) return 0.0;
  if (!(r > 0.0)) return std::numeric_limits<double>::infinity();
  const double d = r - r0;
  const double l = std::log(r / r0);
  if (gradient != nullptr) {
    Mat3 cofactor;  // d det F / dF
    cofactor.col(0) = f.col(1).cross(f.col(2));
    cofactor.col(1) = f.col(2).cross(f.col(0));
    cofactor.col(2) = f.col(0).cross(f.col(1));
    *gradient = (kappa * (-2.0 * d * l - d * d / r) / target) * cofactor;
  }
  return -kappa * d * d * l;
}

Vec12 stack_corners(const TetCorners& p) {
  Vec12 v;
  for (int i = 0; i < 4; ++i) v.segment<3>(3 * i) = p[i];
  return v;
}

}  // namespace forensim
