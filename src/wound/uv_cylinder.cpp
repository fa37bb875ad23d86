#include "wound/uv_cylinder.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace forensim {

TriMesh make_uv_cylinder(double radius_mm, double length_mm, int segments, int rings) {
  if (!(radius_mm > 0.0) || !(length_mm > 0.0) || !std::isfinite(radius_mm) || !std::isfinite(length_mm) ||
      segments < 3 || rings < 1 || segments > 100000 || rings > 100000) {
    throw InputError("uv cylinder", "options", "radius and length must be positive, segments >= 3, rings >= 1");
  }
  TriMesh m;
  const double circumference = 2.0 * M_PI * radius_mm;
  const double s = std::max(circumference, length_mm);
  for (int r = 0; r <= rings; ++r) {
    const double z = length_mm * r / rings;
    for (int k = 0; k < segments; ++k) {
      const double a = 2.0 * M_PI * k / segments;
      m.positions.push_back(Vec3(radius_mm * std::cos(a), radius_mm * std::sin(a), z));
      m.normals.push_back(Vec3(std::cos(a), std::sin(a), 0.0));
    }
    for (int k = 0; k <= segments; ++k) m.uvs.push_back(Vec2(circumference * k / segments / s, z / s));
  }
  auto vid = [&](int r, int k) { return static_cast<Index>(r * segments + (k % segments)); };
  auto uid = [&](int r, int k) { return static_cast<Index>(r * (segments + 1) + k); };
  for (int r = 0; r < rings; ++r) {
    for (int k = 0; k < segments; ++k) {
      // Outward facing: counter-clockwise seen from outside (angle increases to the left looking inward).
      m.triangles.push_back({vid(r, k), vid(r, k + 1), vid(r + 1, k + 1)});
      m.triangle_uvs.push_back({uid(r, k), uid(r, k + 1), uid(r + 1, k + 1)});
      m.triangles.push_back({vid(r, k), vid(r + 1, k + 1), vid(r + 1, k)});
      m.triangle_uvs.push_back({uid(r, k), uid(r + 1, k + 1), uid(r + 1, k)});
    }
  }
  m.material.name = "skin";
  return m;
}

}  // namespace forensim
