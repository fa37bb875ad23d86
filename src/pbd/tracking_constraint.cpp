#include "pbd/tracking_constraint.hpp"

#include <algorithm>

namespace forensim {

double tracking_value(const Vec3& p, const Vec3& t, double radius) {
  return (t - p).norm() - radius;
}

PairCorrection project_tracking(const Vec3& p, const Vec3& t, double w_p, double w_t, double radius, double stiffness) {
  PairCorrection out;
  const double w = w_p + w_t;
  const Vec3 d = p - t;
  const double length = d.norm();
  const double c = length - radius;
  if (w <= 0.0 || length <= 0.0 || c <= 0.0) return out;
  const Vec3 n = d / length;
  const double s = stiffness * c / w;
  out.dp0 = -w_p * s * n;
  out.dp1 = w_t * s * n;
  return out;
}

Vec3 project_tracking_bounded(const Vec3& p, const Vec3& a, double radius, double stiffness, double bound) {
  const Vec3 d = p - a;
  const double length = d.norm();
  double target = length;
  if (length > radius) target = length - stiffness * (length - radius);
  target = std::min(target, bound);
  if (!(length > 0.0) || target >= length) return Vec3::Zero();
  return ((target - length) / length) * d;
}

Vec3 tracking_pull(const Vec3& p, const Vec3& t, double radius, double stiffness) {
  return project_tracking(p, t, 1.0, 0.0, radius, stiffness).dp0;
}

}  // namespace forensim
