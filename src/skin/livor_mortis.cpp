#include "skin/livor_mortis.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {

namespace {

double smoothstep_signed(double x) {  // 0 at x <= -1, 1 at x >= 1
  if (x <= -1.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double t = 0.5 * (x + 1.0);
  return t * t * (3.0 - 2.0 * t);
}

Vec3 unit_gravity(const Vec3& gravity, const std::string& source) {
  require_input(gravity.allFinite() && gravity.norm() > 1e-12, source, "gravity", "must be a non-zero vector");
  return gravity.normalized();
}

std::vector<double> vertex_areas(const TriMesh& mesh) {
  std::vector<double> area(mesh.vertex_count(), 0.0);
  for (const Tri& t : mesh.triangles) {
    const double a = triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]) / 3.0;
    for (Index v : t) area[static_cast<std::size_t>(v)] += a;
  }
  return area;
}

}  // namespace

std::vector<std::uint8_t> contact_near_plane(const TriMesh& skin, const Vec3& gravity, double distance_mm,
                                             double plane_offset_mm) {
  const Vec3 up = -unit_gravity(gravity, "contact plane");
  require_input(std::isfinite(distance_mm) && distance_mm >= 0.0, "contact plane", "distance_mm", "must be >= 0");
  require_input(std::isfinite(plane_offset_mm), "contact plane", "plane_offset_mm", "must be finite");
  std::vector<std::uint8_t> mask(skin.vertex_count(), 0);
  if (skin.positions.empty()) return mask;
  double lowest = skin.positions[0].dot(up);
  for (const Vec3& p : skin.positions) lowest = std::min(lowest, p.dot(up));
  const double plane = lowest + plane_offset_mm;
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = skin.positions[i].dot(up) - plane <= distance_mm ? 1 : 0;
  return mask;
}

std::vector<std::uint8_t> vertex_mask_from_faces(const TriMesh& skin, const std::vector<std::uint8_t>& face_mask) {
  require_input(face_mask.size() == skin.triangle_count(), "contact face mask", "",
                "has " + std::to_string(face_mask.size()) + " entries for " + std::to_string(skin.triangle_count()) +
                    " triangles");
  std::vector<std::uint8_t> mask(skin.vertex_count(), 0);
  for (std::size_t f = 0; f < face_mask.size(); ++f)
    if (face_mask[f])
      for (Index v : skin.triangles[f]) mask[static_cast<std::size_t>(v)] = 1;
  return mask;
}

LivorState settle_livor(const TriMesh& skin, const std::vector<std::uint8_t>& contact, const LivorSettings& s,
                        const std::vector<double>& capacity) {
  const std::string src = "livor mortis";
  const std::size_t n = skin.vertex_count();
  require_input(n > 0 && skin.triangle_count() > 0, src, "skin", "mesh is empty");
  require_input(contact.empty() || contact.size() == n, src, "contact",
                "has " + std::to_string(contact.size()) + " entries for " + std::to_string(n) + " vertices");
  require_input(capacity.empty() || capacity.size() == n, src, "capacity",
                "has " + std::to_string(capacity.size()) + " entries for " + std::to_string(n) + " vertices");
  require_input(std::isfinite(s.residual_fill) && s.residual_fill >= 0.0, src, "residual_fill", "must be >= 0");
  require_input(std::isfinite(s.blood_fill) && s.blood_fill > s.residual_fill && s.blood_fill <= 1.0, src, "blood_fill",
                "must be in (residual_fill, 1]");
  require_input(std::isfinite(s.contact_capacity) && s.contact_capacity >= 0.0 && s.contact_capacity <= 1.0, src,
                "contact_capacity", "must be in [0, 1]");
  require_input(std::isfinite(s.oxygen) && s.oxygen >= 0.0 && s.oxygen <= 1.0, src, "oxygen", "must be in [0, 1]");
  require_input(std::isfinite(s.transition_fraction) && s.transition_fraction > 0.0, src, "transition_fraction",
                "must be positive");
  require_input(std::isfinite(s.transition_mm), src, "transition_mm", "must be finite");
  for (std::size_t i = 0; i < capacity.size(); ++i)
    require_input(std::isfinite(capacity[i]) && capacity[i] >= 0.0 && capacity[i] <= 1.0, src,
                  "capacity[" + std::to_string(i) + "]", "must be in [0, 1]");
  const Vec3 up = -unit_gravity(s.gravity, src);

  LivorState state;
  std::vector<double> height(n);
  state.height_min_mm = state.height_max_mm = skin.positions[0].dot(up);
  for (std::size_t i = 0; i < n; ++i) {
    height[i] = skin.positions[i].dot(up);
    state.height_min_mm = std::min(state.height_min_mm, height[i]);
    state.height_max_mm = std::max(state.height_max_mm, height[i]);
  }
  const double range = std::max(state.height_max_mm - state.height_min_mm, 1e-9);
  const double w = s.transition_mm > 0.0 ? s.transition_mm : s.transition_fraction * range;
  state.transition_mm = w;

  const std::vector<double> area = vertex_areas(skin);
  state.vertex_contact = contact.empty() ? std::vector<std::uint8_t>(n, 0) : contact;
  state.vertex_capacity.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double m0 = capacity.empty() ? 1.0 : capacity[i];
    state.vertex_capacity[i] = state.vertex_contact[i] ? s.contact_capacity * m0 : m0;
  }
  const double target = s.blood_fill * parallel_sum(0, n, [&](std::size_t i) {
                          return area[i] * (capacity.empty() ? 1.0 : capacity[i]);
                        });
  auto fill = [&](double level, std::size_t i) {
    return s.residual_fill + (1.0 - s.residual_fill) * smoothstep_signed((level - height[i]) / w);
  };
  auto volume = [&](double level) {
    return parallel_sum(0, n, [&](std::size_t i) { return area[i] * state.vertex_capacity[i] * fill(level, i); });
  };
  // volume(level) rises monotonically from r * capacity (level below everything) to the full capacity.
  double lo = state.height_min_mm - w, hi = state.height_max_mm + w;
  if (volume(hi) <= target) {
    lo = hi;  // more blood than the vessels hold: all full
  } else if (volume(lo) < target) {
    for (int iter = 0; iter < 200 && hi - lo > 1e-9 * range; ++iter) {
      const double mid = 0.5 * (lo + hi);
      (volume(mid) < target ? lo : hi) = mid;
    }
  } else {
    hi = lo;  // contact capacity so small that the residual alone exceeds the blood: stays at the residual
  }
  state.blood_level_mm = 0.5 * (lo + hi);
  state.vertex_hemoglobin.resize(n);
  state.vertex_saturation.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    state.vertex_hemoglobin[i] = fill(state.blood_level_mm, i);
    state.vertex_saturation[i] = state.vertex_hemoglobin[i] * state.vertex_capacity[i];
  }
  state.vertex_oxygen.assign(n, s.oxygen);
  state.blood_volume = volume(state.blood_level_mm);
  return state;
}

}  // namespace forensim
