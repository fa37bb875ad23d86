#pragma once
/// Element kernels of the skin-muscle-skull spring model (skin_muscle_model.hpp): pure functions on fixed-size
/// types. Energies are in the model's stiffness unit times mm^2; only stiffness ratios matter for the static
/// equilibrium the expressions solve for.

#include <Eigen/Core>

#include "core/types.hpp"

namespace forensim {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// A two-node spring's energy, gradient and Hessian with respect to (x_a, x_b).
struct SpringTerm {
  double energy = 0.0;
  Vec6 gradient = Vec6::Zero();
  Mat6 hessian = Mat6::Zero();
};

/// Spring E = k/2 (l - L)^2 with l = |x_a - x_b| (Kähler et al. 2001, the skin and fibre springs). With
/// `tension_only` the spring only pulls (E = k/2 max(0, l - L)^2: a muscle fibre cannot push). With `project`
/// the Hessian is made positive semi-definite by clamping the transverse factor (1 - L/l) at 0, so Newton
/// steps descend even where springs are compressed. `rest_length` L >= 0 mm, `stiffness` k >= 0. Coincident
/// nodes give zero gradient and the isotropic Hessian k I.
SpringTerm spring_term(const Vec3& x_a, const Vec3& x_b, double rest_length, double stiffness, bool tension_only,
                       bool project);

/// Energy and force of the spring of spring_term() without its Hessian (the quasi-Newton solver's inner loop):
/// E = k/2 (l - L)^2 and its gradient with respect to x_a, k (l - L) (x_a - x_b) / l (the gradient with
/// respect to x_b is its negative). Coincident nodes give zero gradient.
struct SpringForce {
  double energy = 0.0;
  Vec3 gradient_a = Vec3::Zero();
};
SpringForce spring_force(const Vec3& x_a, const Vec3& x_b, double rest_length, double stiffness);

/// Energy of a zero-length vector spring between a point on a triangle (barycentric `weights` of its corner
/// positions x_0..x_2) and a node y, offset by the rest vector `offset`: E = k/2 |sum_i w_i x_i - y - offset|^2
/// (the attachment of a muscle fibre node to the skin above it). Returns the residual vector
/// r = sum_i w_i x_i - y - offset; the gradient with respect to x_i is k w_i r, to y is -k r, and the Hessian
/// is k c c^T (x) I_3 with c = (w_0, w_1, w_2, -1).
Vec3 attachment_residual(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& y, const Vec3& weights,
                         const Vec3& offset);

}  // namespace forensim
