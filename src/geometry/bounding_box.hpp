#pragma once
/// Axis-aligned bounding boxes.

#include <limits>
#include <vector>

#include "core/types.hpp"

namespace forensim {

struct BoundingBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return (max.array() < min.array()).any(); }
  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const BoundingBox& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
  Vec3 size() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
  Vec3 center() const { return 0.5 * (min + max); }
  double diagonal() const { return size().norm(); }
  bool contains(const Vec3& p) const { return (p.array() >= min.array()).all() && (p.array() <= max.array()).all(); }
};

/// Bounding box of a point set.
BoundingBox bounding_box(const std::vector<Vec3>& points);

}  // namespace forensim
