#include "volume/vdb_polygons.hpp"

namespace forensim {

TriMesh mesh_from_vdb_polygons(std::vector<Vec3> positions, const std::vector<openvdb::Vec3I>& triangles,
                               const std::vector<openvdb::Vec4I>& quads, bool reverse) {
  TriMesh mesh;
  mesh.positions = std::move(positions);
  const auto add = [&](Index a, Index b, Index c) { mesh.triangles.push_back(reverse ? Tri{a, c, b} : Tri{a, b, c}); };
  mesh.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const auto& t : triangles) add(Index(t[0]), Index(t[1]), Index(t[2]));
  for (const auto& q : quads) {
    const Index a = Index(q[0]), b = Index(q[1]), c = Index(q[2]), d = Index(q[3]);
    const double ac = (mesh.positions[std::size_t(a)] - mesh.positions[std::size_t(c)]).squaredNorm();
    const double bd = (mesh.positions[std::size_t(b)] - mesh.positions[std::size_t(d)]).squaredNorm();
    if (ac <= bd) {
      add(a, b, c);
      add(a, c, d);
    } else {
      add(a, b, d);
      add(b, c, d);
    }
  }
  return mesh;
}

}  // namespace forensim
