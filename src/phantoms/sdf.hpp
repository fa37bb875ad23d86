#pragma once
/// Signed distance functions (negative inside, millimetres) and their smooth combinations: the modelling
/// language of forensim's procedural phantoms. Small value functions, evaluated millions of times.

#include <algorithm>
#include <cmath>

#include "core/types.hpp"

namespace forensim::sdf {

/// Sphere of radius r at c.
inline double sphere(const Vec3& p, const Vec3& c, double r) {
  return (p - c).norm() - r;
}

/// Ellipsoid with semi-axes `radii` at c (Inigo Quilez's bound: exact on the surface, close near it).
inline double ellipsoid(const Vec3& p, const Vec3& c, const Vec3& radii) {
  const Vec3 q = (p - c).cwiseQuotient(radii);
  const double k0 = q.norm();
  const double k1 = (p - c).cwiseQuotient(radii.cwiseProduct(radii)).norm();
  return k1 > 0 ? k0 * (k0 - 1.0) / k1 : -radii.minCoeff();
}

/// Capsule from a to b with radii ra at a and rb at b (a tapered, round-capped cylinder).
inline double capsule(const Vec3& p, const Vec3& a, const Vec3& b, double ra, double rb) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double h = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - a - h * ab).norm() - (ra + (rb - ra) * h);
}

/// Box with half-extents `half` at c, corners rounded by `radius`.
inline double rounded_box(const Vec3& p, const Vec3& c, const Vec3& half, double radius) {
  const Vec3 q = (p - c).cwiseAbs() - half + Vec3::Constant(radius);
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - radius;
}

/// Union with a smooth blend of width k (polynomial smooth minimum).
inline double smooth_union(double a, double b, double k) {
  if (k <= 0) return std::min(a, b);
  const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h - k * h * (1.0 - h);
}

/// a minus b with a smooth blend of width k.
inline double smooth_subtract(double a, double b, double k) {
  return -smooth_union(-a, b, k);
}

/// Shell of thickness t around the surface of d (|d| - t/2).
inline double shell(double d, double thickness) {
  return std::abs(d) - 0.5 * thickness;
}

}  // namespace forensim::sdf
