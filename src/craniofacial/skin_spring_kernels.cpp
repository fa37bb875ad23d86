#include "craniofacial/skin_spring_kernels.hpp"

#include <algorithm>

namespace forensim {

SpringTerm spring_term(const Vec3& x_a, const Vec3& x_b, double rest_length, double stiffness, bool tension_only,
                       bool project) {
  SpringTerm t;
  const Vec3 d = x_a - x_b;
  const double l = d.norm();
  if (l <= 0.0) {
    // Degenerate: treat as isotropic (only reached for coincident nodes).
    t.hessian.topLeftCorner<3, 3>() = stiffness * Mat3::Identity();
    t.hessian.bottomRightCorner<3, 3>() = stiffness * Mat3::Identity();
    t.hessian.topRightCorner<3, 3>() = -stiffness * Mat3::Identity();
    t.hessian.bottomLeftCorner<3, 3>() = -stiffness * Mat3::Identity();
    return t;
  }
  const double stretch = l - rest_length;
  if (tension_only && stretch <= 0.0) return t;
  const Vec3 n = d / l;
  t.energy = 0.5 * stiffness * stretch * stretch;
  const Vec3 g = stiffness * stretch * n;
  t.gradient.head<3>() = g;
  t.gradient.tail<3>() = -g;
  double transverse = 1.0 - rest_length / l;
  if (project) transverse = std::max(transverse, 0.0);
  const Mat3 block = stiffness * (transverse * Mat3::Identity() + (rest_length / l) * (n * n.transpose()));
  t.hessian.topLeftCorner<3, 3>() = block;
  t.hessian.bottomRightCorner<3, 3>() = block;
  t.hessian.topRightCorner<3, 3>() = -block;
  t.hessian.bottomLeftCorner<3, 3>() = -block;
  return t;
}

SpringForce spring_force(const Vec3& x_a, const Vec3& x_b, double rest_length, double stiffness) {
  SpringForce f;
  const Vec3 d = x_a - x_b;
  const double l = d.norm();
  const double stretch = l - rest_length;
  f.energy = 0.5 * stiffness * stretch * stretch;
  if (l > 0.0) f.gradient_a = (stiffness * stretch / l) * d;
  return f;
}

Vec3 attachment_residual(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& y, const Vec3& weights,
                         const Vec3& offset) {
  return weights(0) * x0 + weights(1) * x1 + weights(2) * x2 - y - offset;
}

}  // namespace forensim
