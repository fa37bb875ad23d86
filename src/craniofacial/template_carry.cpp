#include "craniofacial/template_carry.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {
namespace {

/// Maps every point of `points` in place; throws naming `what` when a mapped point is not finite.
void carry(std::vector<Vec3>& points, const SkullRegistration& registration, const std::string& what) {
  parallel_for(0, points.size(), [&](std::size_t i) { points[i] = registration.map(points[i]); });
  for (const Vec3& p : points) {
    if (!p.allFinite()) {
      throw InputError("template head", what, "the skull registration maps a point to a non-finite position");
    }
  }
}

}  // namespace

TemplateHead carry_template_head(const TemplateHead& head, const SkullRegistration& registration) {
  require_input(!head.skin.triangles.empty(), "template head", "skin", "has no triangles");
  require_input(!head.skull.triangles.empty(), "template head", "skull", "has no triangles");
  TemplateHead out = head;
  carry(out.skin.positions, registration, "skin");
  compute_normals(out.skin);
  carry(out.skull.positions, registration, "skull");
  compute_normals(out.skull);
  for (MuscleLayout& muscle : out.muscles) carry(muscle.grid, registration, "muscle " + muscle.name);
  std::vector<Vec3> points;
  points.reserve(2 * out.landmarks.size() + out.skin_landmarks.size());
  for (const TemplateLandmarkPair& pair : out.landmarks) {
    points.push_back(pair.skull);
    points.push_back(pair.skin);
  }
  for (const TemplateSkinLandmark& l : out.skin_landmarks) points.push_back(l.position);
  carry(points, registration, "landmarks");
  std::size_t k = 0;
  for (TemplateLandmarkPair& pair : out.landmarks) {
    pair.skull = points[k++];
    pair.skin = points[k++];
    const Vec3 segment = pair.skin - pair.skull;
    pair.depth_mm = segment.norm();
    // A pair whose two points coincide keeps its direction (only a degenerate map could do this).
    if (pair.depth_mm > 0.0) pair.skull_normal = segment / pair.depth_mm;
  }
  for (TemplateSkinLandmark& l : out.skin_landmarks) l.position = points[k++];
  out.source = head.source + ", carried onto the skull by its registration";
  return out;
}

}  // namespace forensim
