#include "texture/uv_seams.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace forensim {

std::vector<UvSeamEdge> uv_seam_edges(const TriMesh& mesh, double tolerance) {
  std::vector<UvSeamEdge> out;
  if (!mesh.has_uvs()) return out;
  std::map<std::pair<Index, Index>, std::pair<std::size_t, int>> first;
  // UV of edge k's midpoint in triangle f, moved `nudge` of the way to the third corner.
  auto uv_mid = [&](std::size_t f, int k, double nudge) {
    const auto& tu = mesh.triangle_uvs[f];
    const Vec2 a = mesh.uvs[tu[k]], b = mesh.uvs[tu[(k + 1) % 3]], c = mesh.uvs[tu[(k + 2) % 3]];
    const Vec2 m = 0.5 * (a + b);
    return Vec2(m + nudge * (c - m));
  };
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index v0 = mesh.triangles[f][k], v1 = mesh.triangles[f][(k + 1) % 3];
      const auto key = std::minmax(v0, v1);
      const auto it = first.find(key);
      if (it == first.end()) {
        first[key] = {f, k};
        continue;
      }
      const auto [g, j] = it->second;
      if ((uv_mid(g, j, 0.0) - uv_mid(f, k, 0.0)).norm() < tolerance) continue;
      out.push_back({0.5 * (mesh.positions[v0] + mesh.positions[v1]), uv_mid(g, j, 0.02), uv_mid(f, k, 0.02), g, f});
    }
  }
  return out;
}

}  // namespace forensim
