#include "mesh_io/uv_seam_split.hpp"

#include <cstdint>
#include <unordered_map>

namespace forensim {

SeamSplitMesh split_uv_seams(const TriMesh& mesh) {
  SeamSplitMesh out;
  out.triangles = mesh.triangles;
  if (!mesh.has_uvs()) {
    out.source_vertex.resize(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) out.source_vertex[v] = static_cast<Index>(v);
    return out;
  }
  std::unordered_map<std::uint64_t, Index> split_of;  // (vertex << 32 | uv) -> split vertex
  split_of.reserve(mesh.positions.size() * 2);
  std::vector<bool> used(mesh.positions.size(), false);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index v = mesh.triangles[f][c];
      const Index uv = mesh.triangle_uvs[f][c];
      const std::uint64_t key =
          (static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)) << 32) | static_cast<std::uint32_t>(uv);
      const auto [it, inserted] = split_of.try_emplace(key, static_cast<Index>(out.source_vertex.size()));
      if (inserted) {
        out.source_vertex.push_back(v);
        out.uvs.push_back(mesh.uvs[static_cast<std::size_t>(uv)]);
        used[static_cast<std::size_t>(v)] = true;
      }
      out.triangles[f][c] = it->second;
    }
  }
  for (std::size_t v = 0; v < used.size(); ++v) {
    if (used[v]) continue;
    out.source_vertex.push_back(static_cast<Index>(v));
    out.uvs.push_back(Vec2::Zero());
  }
  return out;
}

}  // namespace forensim
