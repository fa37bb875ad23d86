#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "fem/tet_element.hpp"

using namespace forensim;

namespace {

TetCorners skewed_tet() {
  return {Vec3(0.1, -0.2, 0.05), Vec3(2.0, 0.3, -0.1), Vec3(0.4, 1.7, 0.2), Vec3(0.3, 0.5, 1.4)};
}

Mat3 rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

TetCorners apply(const TetCorners& p, const Mat3& a, const Vec3& shift) {
  TetCorners q;
  for (int i = 0; i < 4; ++i) q[i] = a * p[i] + shift;
  return q;
}

}  // namespace

TEST(TetElement, ShapeGradientsReproduceLinearFunctions) {
  const TetCorners p = skewed_tet();
  double volume = 0.0;
  const Mat34 g = tet_shape_gradients(p, &volume);
  EXPECT_NEAR(volume, tet_volume(p), 1e-14);
  EXPECT_GT(volume, 0.0);
  const Vec3 a(0.7, -1.3, 2.1);
  Vec3 grad = Vec3::Zero();
  for (int i = 0; i < 4; ++i) grad += (a.dot(p[i]) + 5.0) * g.col(i);
  EXPECT_LT((grad - a).norm(), 1e-12);
  EXPECT_LT(g.rowwise().sum().norm(), 1e-12);
}

TEST(TetElement, DiffusionStiffnessIsSymmetricPsdWithZeroRowSums) {
  const TetCorners p = skewed_tet();
  double volume = 0.0;
  const Mat34 g = tet_shape_gradients(p, &volume);
  const Mat4 k = tet_diffusion_stiffness(g, volume, 2.5);
  EXPECT_LT((k - k.transpose()).norm(), 1e-14);
  EXPECT_LT(k.rowwise().sum().norm(), 1e-12);
  const Eigen::SelfAdjointEigenSolver<Mat4> eig(k);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12);
  EXPECT_GT(eig.eigenvalues()[1], 1e-6);  // only constants in the kernel
  // Energy of a linear field: k V |grad u|^2.
  const Vec3 a(1.0, 2.0, -0.5);
  Vec4 u;
  for (int i = 0; i < 4; ++i) u[i] = a.dot(p[i]);
  EXPECT_NEAR(u.dot(k * u), 2.5 * volume * a.squaredNorm(), 1e-10);
}

TEST(TetElement, MassesSumToVolumeTimesCoefficient) {
  EXPECT_NEAR(tet_consistent_mass(0.3, 2.0).sum(), 0.6, 1e-14);
  EXPECT_NEAR(tet_lumped_mass(0.3, 2.0).sum(), 0.6, 1e-14);
  // Row sums of the consistent mass equal the lumped mass.
  EXPECT_LT((tet_consistent_mass(0.3, 2.0).rowwise().sum() - tet_lumped_mass(0.3, 2.0)).norm(), 1e-15);
}

TEST(TetElement, RobinTermsIntegrateOverTheTriangle) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 3, 0);
  const Mat3 h = triangle_robin_matrix(a, b, c, 0.5);
  EXPECT_NEAR(h.sum(), 0.5 * 3.0, 1e-14);
  EXPECT_LT((h - h.transpose()).norm(), 1e-15);
  EXPECT_NEAR(triangle_robin_load(a, b, c, 0.5, 0.2).sum(), 0.5 * 0.2 * 3.0, 1e-14);
}

TEST(TetElement, LinearStiffnessKernelIsRigidMotions) {
  const TetCorners p = skewed_tet();
  double volume = 0.0;
  const Mat34 g = tet_shape_gradients(p, &volume);
  const Mat12 k = tet_linear_stiffness(g, volume, 1e4, 0.3);
  EXPECT_LT((k - k.transpose()).norm(), 1e-9 * k.norm());
  const Eigen::SelfAdjointEigenSolver<Mat12> eig(k);
  const auto ev = eig.eigenvalues();
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev[i]), 1e-9 * ev[11]);
  EXPECT_GT(ev[6], 1e-6 * ev[11]);
  // Uniform dilation u = e x gives the elastic energy V/2 eps:C:eps with eps = e I.
  Vec12 u;
  for (int i = 0; i < 4; ++i) u.segment<3>(3 * i) = 0.01 * p[i];
  const Vec2 lame = lame_parameters(1e4, 0.3);
  EXPECT_NEAR(0.5 * u.dot(k * u), 0.5 * volume * (3 * lame[0] + 2 * lame[1]) * 3 * 1e-4, 1e-9);
}

TEST(TetElement, PolarRotationRecoversRotationAndStaysProperWhenInverted) {
  const Mat3 q = rotation(0.8, Vec3(1, 2, 3));
  Mat3 s;
  s << 1.2, 0.1, 0.0, 0.1, 0.9, 0.05, 0.0, 0.05, 1.1;
  EXPECT_LT((rotation_from_deformation(q * s) - q).norm(), 1e-12);
  Mat3 inverted = q * s;
  inverted.col(0) = -inverted.col(0);
  const Mat3 r = rotation_from_deformation(inverted);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_LT((r.transpose() * r - Mat3::Identity()).norm(), 1e-12);
}

TEST(TetElement, CorotationalForceVanishesUnderRigidMotion) {
  const TetCorners rest = skewed_tet();
  double volume = 0.0;
  const Mat34 g = tet_shape_gradients(rest, &volume);
  const Mat12 k = tet_linear_stiffness(g, volume, 5e3, 0.45);
  const Mat3 rinv = tet_rest_edge_inverse(rest);
  for (double angle : {0.3, 1.5, 3.0}) {
    const Mat3 q = rotation(angle, Vec3(-1, 0.5, 2));
    const TetCorners x = apply(rest, q, Vec3(10, -3, 7));
    const Mat3 r = rotation_from_deformation(tet_deformation_gradient(x, rinv));
    EXPECT_LT((r - q).norm(), 1e-12);
    const Vec12 f = tet_corotational_force(k, r, stack_corners(x), stack_corners(rest), Vec12::Zero());
    EXPECT_LT(f.norm(), 1e-9 * k.norm()) << "angle " << angle;
    // The linear (unwarped) force is not zero: the reason for warping.
    EXPECT_GT((k * (stack_corners(x) - stack_corners(rest))).norm(), 1e-3 * k.norm());
  }
}

TEST(TetElement, EigenstrainForceVanishesAtTheShrunkShape) {
  const TetCorners rest = skewed_tet();
  double volume = 0.0;
  const Mat34 g = tet_shape_gradients(rest, &volume);
  const Mat6 c = isotropic_elasticity(1e4, 0.3);
  const Mat12 k = volume * tet_strain_matrix(g).transpose() * c * tet_strain_matrix(g);
  const double s = -0.1;
  const Mat3 q = rotation(2.0, Vec3(0.3, 1, -1));
  const TetCorners x = apply(rest, (1.0 + s) * q, Vec3(1, 2, 3));
  const Mat3 r = rotation_from_deformation(tet_deformation_gradient(x, tet_rest_edge_inverse(rest)));
  const Vec12 f =
      tet_corotational_force(k, r, stack_corners(x), stack_corners(rest), tet_eigenstrain_force(g, volume, c, s));
  EXPECT_LT(f.norm(), 1e-9 * k.norm());
  EXPECT_NEAR(tet_volume(x) / volume, std::pow(1.0 + s, 3), 1e-12);
}

TEST(TetElement, CorotationalForceIsMinusEnergyGradient) {
  const TetCorners rest = skewed_tet();
  double volume = 0.0;
  const Mat34 g = tet_shape_gradients(rest, &volume);
  const Mat6 c = isotropic_elasticity(2e4, 0.35);
  const Mat12 k = volume * tet_strain_matrix(g).transpose() * c * tet_strain_matrix(g);
  const Mat3 rinv = tet_rest_edge_inverse(rest);
  for (double s : {0.0, -0.08}) {
    // A rotated, moderately deformed configuration (well beyond the linear regime).
    Mat3 a;
    a << 1.1, 0.15, -0.05, 0.02, 0.92, 0.1, -0.07, 0.04, 1.05;
    const TetCorners x = apply(rest, rotation(0.9, Vec3(1, 1, 0)) * a, Vec3(0.5, 0, -1));
    const Mat3 r = rotation_from_deformation(tet_deformation_gradient(x, rinv));
    const Vec12 f =
        tet_corotational_force(k, r, stack_corners(x), stack_corners(rest), tet_eigenstrain_force(g, volume, c, s));
    const double step = 1e-6;
    for (int i = 0; i < 12; ++i) {
      TetCorners plus = x, minus = x;
      plus[i / 3][i % 3] += step;
      minus[i / 3][i % 3] -= step;
      const double fd =
          -(tet_corotational_energy(plus, rinv, volume, c, s) - tet_corotational_energy(minus, rinv, volume, c, s)) /
          (2 * step);
      EXPECT_NEAR(f[i], fd, 1e-6 * f.norm()) << "dof " << i << " s " << s;
    }
  }
}

TEST(TetElement, NewtonPolarRotationMatchesTheSvd) {
  Mat3 s;
  s << 1.2, 0.1, 0.0, 0.1, 0.9, 0.05, 0.0, 0.05, 1.1;
  for (double angle : {0.0, 0.8, 3.1}) {
    for (double scale : {1.0, 0.55, 1e-3, 40.0}) {
      const Mat3 q = rotation(angle, Vec3(1, 2, 3));
      const Mat3 f = scale * q * s;
      const Mat3 r = polar_rotation(f);
      EXPECT_LT((r - q).norm(), 1e-12) << angle << " " << scale;
      EXPECT_LT((r - rotation_from_deformation(f)).norm(), 1e-12);
    }
  }
  // Strongly sheared and inverted gradients: still a proper rotation, the SVD's where inverted.
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 4.0;
  EXPECT_LT((polar_rotation(shear) - rotation_from_deformation(shear)).norm(), 1e-12);
  Mat3 inverted = rotation(0.8, Vec3(1, 2, 3)) * s;
  inverted.col(0) = -inverted.col(0);
  EXPECT_NEAR(polar_rotation(inverted).determinant(), 1.0, 1e-12);
  EXPECT_LT((polar_rotation(inverted) - rotation_from_deformation(inverted)).norm(), 1e-12);
}

TEST(TetElement, BatchedPolarRotationsAreTheLoneOnesBitForBit) {
  // Mixed batches (lengths not multiples of the lane group): mild and strong stretches, an inverted and a
  // singular gradient (SVD fallback). Each result must equal polar_rotation exactly, whatever its neighbours
  // in the batch.
  Mat3 s;
  s << 1.2, 0.1, 0.0, 0.1, 0.9, 0.05, 0.0, 0.05, 1.1;
  std::vector<Mat3> f;
  for (int i = 0; i < 37; ++i) {
    const double t = 0.1 * i;
    Mat3 g = rotation(0.3 * i, Vec3(1.0, t, 2.0 - t)) * ((0.7 + 0.02 * i) * s);
    g(0, 1) += (i % 5 == 0) ? 3.0 : 0.0;          // strongly sheared: more iterations than its neighbours
    if (i % 7 == 3) g.col(0) = -g.col(0);         // inverted
    if (i == 11) g.col(2) = g.col(0) + g.col(1);  // singular
    f.push_back(g);
  }
  for (std::size_t count : {std::size_t{1}, std::size_t{5}, std::size_t{8}, std::size_t{37}}) {
    std::vector<Mat3> r(count);
    polar_rotations(f.data(), r.data(), count);
    for (std::size_t i = 0; i < count; ++i) {
      const Mat3 lone = polar_rotation(f[i]);
      for (int k = 0; k < 9; ++k) EXPECT_EQ(r[i](k), lone(k)) << "matrix " << i << " of " << count;
      if (std::abs(f[i].determinant()) > 1e-9) {
        EXPECT_NEAR(r[i].determinant(), 1.0, 1e-12) << i;
        EXPECT_LT((r[i] - rotation_from_deformation(f[i])).norm(), 1e-11) << i;
      }
    }
  }
}

TEST(TetElement, CorotatedStressGivesTheElementForceAndStiffness) {
  // -V R sigma G (columns: corner forces) must equal tet_corotational_force, and V R sigma(R^T grad v) G the
  // warped stiffness R K R^T applied to v.
  const TetCorners rest = skewed_tet();
  double volume = 0.0;
  const Mat34 g = tet_shape_gradients(rest, &volume);
  const double e = 2e4, nu = 0.35, s = -0.07;
  const Vec2 lame = lame_parameters(e, nu);
  const Mat6 c = isotropic_elasticity(e, nu);
  const Mat12 k = tet_linear_stiffness(g, volume, e, nu);
  Mat3 a;
  a << 1.1, 0.15, -0.05, 0.02, 0.92, 0.1, -0.07, 0.04, 1.05;
  const TetCorners x = apply(rest, rotation(0.9, Vec3(1, 1, 0)) * a, Vec3(0.5, 0, -1));
  Mat34 xc, vc;
  for (int i = 0; i < 4; ++i) {
    xc.col(i) = x[i];
    vc.col(i) = Vec3(std::sin(i + 1.0), std::cos(2.0 * i), 0.3 * i - 0.5);
  }
  const Mat3 f = tet_field_gradient(g, xc);
  EXPECT_LT((f - tet_deformation_gradient(x, tet_rest_edge_inverse(rest))).norm(), 1e-12);
  const Mat3 r = polar_rotation(f);
  const Mat34 force = -volume * (r * corotated_stress(r, f, lame[0], lame[1], s)) * g;
  const Vec12 expected =
      tet_corotational_force(k, r, stack_corners(x), stack_corners(rest), tet_eigenstrain_force(g, volume, c, s));
  const Mat34 product = volume * (r * corotated_stress(r, tet_field_gradient(g, vc), lame[0], lame[1], -1.0)) * g;
  Vec12 v;
  for (int i = 0; i < 4; ++i) v.segment<3>(3 * i) = vc.col(i);
  const Vec12 expected_product = rotate_stiffness(r, k) * v;
  for (int i = 0; i < 12; ++i) {
    EXPECT_NEAR(force(i % 3, i / 3), expected[i], 1e-10 * expected.norm()) << i;
    EXPECT_NEAR(product(i % 3, i / 3), expected_product[i], 1e-10 * expected_product.norm()) << i;
  }
}

TEST(TetElement, VolumeBarrierIsZeroAboveItsRangeAndInfiniteWhenTurnedOver) {
  const double s = -0.3, kappa = 7.0, r0 = 0.5;
  const double target = std::pow(1.0 + s, 3);
  const Mat3 q = rotation(0.7, Vec3(1, 2, -1));
  Mat3 gradient;
  // A rotated copy at 0.6 of the target volume: outside the barrier's range.
  EXPECT_EQ(tet_volume_barrier(std::cbrt(0.6 * target) * q, s, kappa, r0, &gradient), 0.0);
  EXPECT_EQ(gradient.norm(), 0.0);
  // Inside: positive, growing as the tet is squeezed; infinite once it turns over.
  const double at_04 = tet_volume_barrier(std::cbrt(0.4 * target) * q, s, kappa, r0, nullptr);
  const double at_01 = tet_volume_barrier(std::cbrt(0.1 * target) * q, s, kappa, r0, nullptr);
  EXPECT_GT(at_04, 0.0);
  EXPECT_GT(at_01, at_04);
  EXPECT_NEAR(at_04, -kappa * 0.01 * std::log(0.8), 1e-12);
  Mat3 flipped = q;
  flipped.col(2) *= -0.5;
  EXPECT_TRUE(std::isinf(tet_volume_barrier(flipped, s, kappa, r0, nullptr)));
  // Switched off.
  EXPECT_EQ(tet_volume_barrier(std::cbrt(0.1 * target) * q, s, kappa, 0.0, nullptr), 0.0);
}

TEST(TetElement, VolumeBarrierGradientMatchesFiniteDifferences) {
  const double s = -0.2, kappa = 3.0, r0 = 0.5;
  Mat3 f;
  f << 0.45, 0.08, -0.03, -0.05, 0.52, 0.06, 0.02, -0.04, 0.38;  // det F / (1 + s)^3 about 0.18
  Mat3 gradient;
  const double psi = tet_volume_barrier(f, s, kappa, r0, &gradient);
  ASSERT_GT(psi, 0.0);
  const double h = 1e-7;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Mat3 plus = f, minus = f;
      plus(i, j) += h;
      minus(i, j) -= h;
      const double fd =
          (tet_volume_barrier(plus, s, kappa, r0, nullptr) - tet_volume_barrier(minus, s, kappa, r0, nullptr)) /
          (2.0 * h);
      EXPECT_NEAR(gradient(i, j), fd, 1e-6 * gradient.norm()) << i << ", " << j;
    }
  }
}
