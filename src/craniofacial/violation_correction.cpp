#include "craniofacial/violation_correction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {
namespace {

struct Candidate {
  double violation_mm = 0.0;  ///< how far the skull pierces the skin (or the skin enters the skull) there
  Vec3 source, skull, normal;
};

Vec3 barycentric_point(const TriMesh& mesh, const ClosestPoint& c) {
  const Tri& t = mesh.triangles[static_cast<std::size_t>(c.triangle)];
  return c.barycentric(0) * mesh.positions[static_cast<std::size_t>(t[0])] +
         c.barycentric(1) * mesh.positions[static_cast<std::size_t>(t[1])] +
         c.barycentric(2) * mesh.positions[static_cast<std::size_t>(t[2])];
}

Vec3 interpolated_normal(const TriMesh& mesh, const ClosestPoint& c) {
  const Tri& t = mesh.triangles[static_cast<std::size_t>(c.triangle)];
  const Vec3 n = c.barycentric(0) * mesh.normals[static_cast<std::size_t>(t[0])] +
                 c.barycentric(1) * mesh.normals[static_cast<std::size_t>(t[1])] +
                 c.barycentric(2) * mesh.normals[static_cast<std::size_t>(t[2])];
  if (n.norm() > 0.0) return n.normalized();
  const Vec3 a = mesh.positions[static_cast<std::size_t>(t[0])], b = mesh.positions[static_cast<std::size_t>(t[1])],
             d = mesh.positions[static_cast<std::size_t>(t[2])];
  return (b - a).cross(d - a).normalized();
}

std::vector<std::size_t> nearest_landmarks(const Vec3& p, const std::vector<Vec3>& landmarks, std::size_t k) {
  std::vector<std::size_t> order(landmarks.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const std::size_t count = std::min(k, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(),
                    [&](std::size_t a, std::size_t b) {
                      const double da = (landmarks[a] - p).squaredNorm(), db = (landmarks[b] - p).squaredNorm();
                      return da < db || (da == db && a < b);
                    });
  order.resize(count);
  return order;
}

}  // namespace

std::vector<Vec3> ViolationCorrectionPairs::targets() const {
  std::vector<Vec3> out(skull.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = skull[i] + depth_mm[i] * normals[i];
  return out;
}

double correction_depth(const std::vector<std::size_t>& neighbours, const std::vector<Vec3>& depth_vectors) {
  require_input(!neighbours.empty(), "correction pair", "neighbours", "no landmark to take the depth from");
  double depth = std::numeric_limits<double>::infinity();
  for (const std::size_t i : neighbours) {
    require_input(i < depth_vectors.size(), "correction pair", "neighbour " + std::to_string(i),
                  "is not one of the " + std::to_string(depth_vectors.size()) + " landmarks");
    depth = std::min(depth, depth_vectors[i].norm());
  }
  return depth;
}

ViolationCorrectionPairs violation_correction_pairs(const TriMesh& skull, const TriMesh& rest_skin,
                                                    const TriMesh& warped_skin, const SkullSkinViolations& violations,
                                                    const std::vector<Vec3>& landmark_skull,
                                                    const std::vector<Vec3>& landmark_depth_vectors,
                                                    const std::vector<Vec3>& existing_sources,
                                                    const std::vector<Vec3>& existing_targets,
                                                    const ViolationCorrectionOptions& options) {
  require_input(!skull.triangles.empty(), "violation correction", "skull", "has no triangles");
  const ClosestPointQuery to_skull(skull);
  return violation_correction_pairs(skull, to_skull, rest_skin, warped_skin, violations, landmark_skull,
                                    landmark_depth_vectors, existing_sources, existing_targets, options);
}

ViolationCorrectionPairs violation_correction_pairs(
    const TriMesh& skull, const ClosestPointQuery& to_skull, const TriMesh& rest_skin, const TriMesh& warped_skin,
    const SkullSkinViolations& violations, const std::vector<Vec3>& landmark_skull,
    const std::vector<Vec3>& landmark_depth_vectors, const std::vector<Vec3>& existing_sources,
    const std::vector<Vec3>& existing_targets, const ViolationCorrectionOptions& options) {
  const char* const source = "violation correction";
  require_input(rest_skin.positions.size() == warped_skin.positions.size() &&
                    rest_skin.triangles.size() == warped_skin.triangles.size(),
                source, "skin", "the warped skin is not the rest skin with moved positions");
  require_input(skull.normals.size() == skull.positions.size(), source, "skull", "has no vertex normals");
  require_input(!landmark_skull.empty() && landmark_skull.size() == landmark_depth_vectors.size(), source, "landmarks",
                "need at least one, with one depth vector each");
  require_input(options.spacing_mm > 0.0 && std::isfinite(options.spacing_mm), source, "spacing_mm",
                "must be positive");
  require_input(options.neighbours >= 1, source, "neighbours", "must be at least 1");

  std::vector<Candidate> candidates;
  if (!violations.skull_vertices_outside.empty()) {
    const ClosestPointQuery to_skin(warped_skin);
    std::vector<Vec3> points;
    for (const std::size_t v : violations.skull_vertices_outside) {
      require_input(v < skull.positions.size(), source, "violations", "skull vertex index out of range");
      points.push_back(skull.positions[v]);
    }
    const auto closest = to_skin.query_batch(points);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::size_t v = violations.skull_vertices_outside[i];
      const Vec3 n = skull.normals[v].norm() > 0.0 ? Vec3(skull.normals[v].normalized()) : Vec3::Zero();
      if (!closest[i] || n.isZero()) continue;
      candidates.push_back({closest[i]->distance, barycentric_point(rest_skin, *closest[i]), points[i], n});
    }
  }
  if (!violations.skin_vertices_inside.empty()) {
    std::vector<Vec3> points;
    for (const std::size_t v : violations.skin_vertices_inside) {
      require_input(v < warped_skin.positions.size(), source, "violations", "skin vertex index out of range");
      points.push_back(warped_skin.positions[v]);
    }
    const auto closest = to_skull.query_batch(points);
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!closest[i]) continue;
      const std::size_t v = violations.skin_vertices_inside[i];
      candidates.push_back(
          {closest[i]->distance, rest_skin.positions[v], closest[i]->point, interpolated_normal(skull, *closest[i])});
    }
  }
  // Deepest first; ties keep the order above (skull vertices, then skin vertices, ascending), so the choice
  // is deterministic.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.violation_mm > b.violation_mm; });

  ViolationCorrectionPairs out;
  const double spacing2 = options.spacing_mm * options.spacing_mm;
  const double existing2 = 0.25 * spacing2;
  std::vector<Vec3> chosen_targets;
  for (const Candidate& c : candidates) {
    if (out.sources.size() >= options.max_pairs) break;
    bool free = true;
    for (const Vec3& p : out.sources) free = free && (p - c.source).squaredNorm() >= spacing2;
    for (const Vec3& p : existing_sources) free = free && (p - c.source).squaredNorm() >= existing2;
    if (!free) continue;
    std::vector<std::size_t> neighbours = nearest_landmarks(c.skull, landmark_skull, options.neighbours);
    const double depth = correction_depth(neighbours, landmark_depth_vectors);
    const Vec3 target = c.skull + depth * c.normal;
    for (const Vec3& q : chosen_targets) free = free && (q - target).squaredNorm() >= existing2;
    for (const Vec3& q : existing_targets) free = free && (q - target).squaredNorm() >= existing2;
    if (!free) continue;
    chosen_targets.push_back(target);
    out.depth_mm.push_back(depth);
    out.neighbours.push_back(std::move(neighbours));
    out.sources.push_back(c.source);
    out.skull.push_back(c.skull);
    out.normals.push_back(c.normal);
  }
  return out;
}

}  // namespace forensim
