#pragma once
/// Bending constraint of position-based dynamics on the dihedral angle of two triangles that share an edge
/// (Mueller et al. 2007, "Position based dynamics", section 4.2 and appendix; Frerichs, Vidler and Gatzidis 2020,
/// section 8.1). Particles: x0 and x1 are the wing vertices, (x2, x3) the shared edge; the triangles are
/// (x0, x2, x3) and (x1, x3, x2), both counter-clockwise from outside. C = theta - theta_0 with theta the signed
/// angle between the two face normals, atan2((nA x nB) . e, nA . nB) in (-pi, pi] (0 for a flat pair). Mueller's
/// acos(nA . nB) is unsigned and its gradient is singular at the flat rest state of a smooth skin; the signed
/// angle with the gradients of Bridson, Marino and Fedkiw 2003 ("Simulation of clothing with folds and
/// wrinkles") is smooth there and tells a fold from its mirror image.

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace forensim {

using Quad = std::array<Vec3, 4>;

/// Signed dihedral angle theta (radians) of the pair (x0, x2, x3), (x1, x3, x2). 0 when a triangle is degenerate.
double dihedral_angle(const Quad& x);

/// theta and its gradient d theta / d x_i (rows 0..3; they sum to zero). Zero gradient for a degenerate pair.
struct DihedralGradient {
  double angle = 0.0;
  std::array<Vec3, 4> gradient{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
};
inline DihedralGradient dihedral_angle_gradient(const Quad& x);

/// angle - rest_angle wrapped into (-pi, pi].
double bending_value(const Quad& x, double rest_angle);

/// Projection (Mueller et al. 2007, eq. 8 and 9): dp_i = -k s w_i grad_i C with s = C / sum_j w_j |grad_j C|^2.
/// `w` inverse masses (>= 0), `stiffness` k in [0, 1]. Zero corrections for a degenerate pair or all fixed.
/// With equal masses sum dp_i = 0 (the gradients sum to zero): linear momentum is conserved.
inline std::array<Vec3, 4> project_bending(const Quad& x, const Vec4& w, double rest_angle, double stiffness);

/// Bending constraints of every interior edge of a triangle mesh (Model data, #B entries each).
struct BendingConstraints {
  std::vector<std::array<Index, 4>> quad_vertices;  ///< #B (x0, x1, x2, x3) as above
  std::vector<double> rest_angle;                   ///< #B theta_0 (radians)
  std::size_t size() const { return quad_vertices.size(); }
};

/// One constraint per edge shared by exactly two consistently oriented triangles (boundary and non-manifold
/// edges get none), rest angles from `positions`. Throws InputError naming `source` for an index out of range.
BendingConstraints make_bending_constraints(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles,
                                            const std::string& source);

// Kernels inline: they run in the solver's innermost loop.
namespace detail {

/// a wrapped into (-pi, pi].
inline double wrap_angle(double a) {
  constexpr double pi = std::numbers::pi;
  while (a > pi) a -= 2.0 * pi;
  while (a <= -pi) a += 2.0 * pi;
  return a;
}

/// theta from the unnormalised face normals and the edge: atan2((nA x nB) . e, (nA . nB) |e|), the same angle
/// as with unit vectors (both arguments carry the factor |nA| |nB| |e|) without three square roots.
inline double angle_from_normals(const Vec3& na, const Vec3& nb, const Vec3& e, double edge_length) {
  return std::atan2(na.cross(nb).dot(e), na.dot(nb) * edge_length);
}

}  // namespace detail

inline DihedralGradient dihedral_angle_gradient(const Quad& x) {
  DihedralGradient out;
  const Vec3 e = x[3] - x[2];
  const Vec3 na = (x[2] - x[0]).cross(x[3] - x[0]);
  const Vec3 nb = (x[3] - x[1]).cross(x[2] - x[1]);
  const double la2 = na.squaredNorm(), lb2 = nb.squaredNorm(), le = e.norm();
  if (la2 <= 0.0 || lb2 <= 0.0 || le <= 0.0) return out;
  out.angle = detail::angle_from_normals(na, nb, e, le);
  // Bridson et al. 2003: |e| nA / |nA|^2 is the wing's gradient up to sign (nA / |nA| over the wing's height).
  const Vec3 a = na / la2, b = nb / lb2;
  const double inv_le = 1.0 / le;
  out.gradient[0] = -le * a;
  out.gradient[1] = -le * b;
  out.gradient[2] = -((x[0] - x[3]).dot(e) * inv_le * a + (x[1] - x[3]).dot(e) * inv_le * b);
  out.gradient[3] = -((x[2] - x[0]).dot(e) * inv_le * a + (x[2] - x[1]).dot(e) * inv_le * b);
  return out;
}

inline std::array<Vec3, 4> project_bending(const Quad& x, const Vec4& w, double rest_angle, double stiffness) {
  std::array<Vec3, 4> dp{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const DihedralGradient g = dihedral_angle_gradient(x);
  double denominator = 0.0;
  for (int i = 0; i < 4; ++i) denominator += w[i] * g.gradient[i].squaredNorm();
  if (!(denominator > 0.0)) return dp;
  const double c = detail::wrap_angle(g.angle - rest_angle);
  const double s = stiffness * c / denominator;
  for (int i = 0; i < 4; ++i) dp[i] = -s * w[i] * g.gradient[i];
  return dp;
}

}  // namespace forensim
