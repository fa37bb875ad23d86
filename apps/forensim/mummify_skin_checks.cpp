#include "mummify_skin_checks.hpp"

#include "geometry/tet_boundary.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/self_intersection.hpp"

namespace forensim::cli {

std::vector<double> part_bone_distance_mm(const BodyModel& body, const std::vector<Vec3>& skin_positions,
                                          const std::vector<Vec3>& node_positions) {
  if (body.part_names.empty() || body.skin_vertex_parts.size() != skin_positions.size()) return {};
  TetMesh volume = body.volume;
  volume.positions = node_positions;
  const TriMesh bone = tet_boundary_mesh(volume, tissue_bone);
  if (bone.triangles.empty()) return {};
  const ClosestPointQuery query(bone);
  const auto closest = query.query_batch(skin_positions);
  std::vector<double> sum(body.part_names.size(), 0.0), count(body.part_names.size(), 0.0);
  for (std::size_t i = 0; i < skin_positions.size(); ++i) {
    if (!closest[i]) continue;
    const auto part = static_cast<std::size_t>(body.skin_vertex_parts[i]);
    sum[part] += closest[i]->distance;
    count[part] += 1.0;
  }
  for (std::size_t p = 0; p < sum.size(); ++p) sum[p] = count[p] > 0.0 ? sum[p] / count[p] : 0.0;
  return sum;
}

std::size_t inverted_skin_triangles(const TriMesh& rest_skin, const std::vector<Vec3>& positions) {
  std::size_t count = 0;
  const std::vector<Vec3>& rest = rest_skin.positions;
  for (const Tri& t : rest_skin.triangles) {
    const auto a = static_cast<std::size_t>(t[0]), b = static_cast<std::size_t>(t[1]),
               c = static_cast<std::size_t>(t[2]);
    const Vec3 n0 = (rest[b] - rest[a]).cross(rest[c] - rest[a]);
    const Vec3 n1 = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
    if (n0.dot(n1) <= 0.0) ++count;
  }
  return count;
}

std::size_t skin_self_intersections(const TriMesh& rest_skin, const std::vector<Vec3>& positions) {
  TriMesh mesh;
  mesh.positions = positions;
  mesh.triangles = rest_skin.triangles;
  return self_intersection_count(mesh);
}

}  // namespace forensim::cli
