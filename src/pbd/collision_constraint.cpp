#include "pbd/collision_constraint.hpp"

namespace forensim {

double collision_value(const Vec3& p, const Vec3& q, const Vec3& normal, double height) {
  return normal.dot(p - q) - height;
}

PairCorrection project_collision(const Vec3& p, const Vec3& q, const Vec3& normal, double w_p, double w_q,
                                 double height, double stiffness) {
  PairCorrection out;
  const double w = w_p + w_q;
  const double c = collision_value(p, q, normal, height);
  if (w <= 0.0 || c >= 0.0) return out;
  const double s = stiffness * c / w;
  out.dp0 = -w_p * s * normal;
  out.dp1 = w_q * s * normal;
  return out;
}

}  // namespace forensim
