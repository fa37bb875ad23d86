#include "craniofacial/skull_skin_violations.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/winding_number.hpp"

namespace forensim {

SkullSkinViolations count_skull_skin_violations(const TriMesh& skull, const TriMesh& skin) {
  require_input(!skull.triangles.empty(), "skull mesh", "", "has no triangles");
  require_input(!skin.triangles.empty(), "skin mesh", "", "has no triangles");
  skull.validate("skull mesh");
  skin.validate("skin mesh");
  SkullSkinViolations v;
  v.skull_vertex_count = skull.positions.size();
  v.skin_vertex_count = skin.positions.size();

  const WindingNumber skin_winding(skin);
  const std::vector<double> w_skin = skin_winding.evaluate_batch(skull.positions);
  std::vector<Vec3> outside;
  for (std::size_t i = 0; i < w_skin.size(); ++i) {
    if (w_skin[i] < 0.5) {
      v.skull_vertices_outside.push_back(i);
      outside.push_back(skull.positions[i]);
    }
  }
  v.skull_outside_skin = outside.size();
  if (!outside.empty()) {
    const ClosestPointQuery to_skin(skin);
    for (const auto& c : to_skin.query_batch(outside))
      v.max_skull_protrusion_mm = std::max(v.max_skull_protrusion_mm, c->distance);
  }

  const WindingNumber skull_winding(skull);
  const std::vector<double> w_skull = skull_winding.evaluate_batch(skin.positions);
  std::vector<Vec3> inside;
  for (std::size_t i = 0; i < w_skull.size(); ++i) {
    if (w_skull[i] > 0.5) {
      v.skin_vertices_inside.push_back(i);
      inside.push_back(skin.positions[i]);
    }
  }
  v.skin_inside_skull = inside.size();
  if (!inside.empty()) {
    const ClosestPointQuery to_skull(skull);
    for (const auto& c : to_skull.query_batch(inside))
      v.max_skin_intrusion_mm = std::max(v.max_skin_intrusion_mm, c->distance);
  }
  return v;
}

}  // namespace forensim
