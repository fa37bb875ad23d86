#pragma once
/// One direction of the Hausdorff distance between surfaces, for the tetrahedraliser's tests.

#include <algorithm>
#include <vector>

#include "geometry/tri_mesh.hpp"
#include "spatial/closest_point.hpp"

namespace tet_test {

/// Largest distance from the points of `from` (vertices and triangle centroids) to the surface `to` (mm).
inline double one_way_distance(const forensim::TriMesh& from, const forensim::TriMesh& to) {
  const forensim::ClosestPointQuery query(to);
  std::vector<forensim::Vec3> points = from.positions;
  for (const forensim::Tri& t : from.triangles)
    points.push_back((from.positions[t[0]] + from.positions[t[1]] + from.positions[t[2]]) / 3.0);
  double worst = 0.0;
  for (const auto& hit : query.query_batch(points)) worst = std::max(worst, hit ? hit->distance : 1e300);
  return worst;
}

}  // namespace tet_test
