#include "geometry/bounding_box.hpp"

namespace forensim {

BoundingBox bounding_box(const std::vector<Vec3>& points) {
  BoundingBox box;
  for (const Vec3& p : points) box.extend(p);
  return box;
}

}  // namespace forensim
