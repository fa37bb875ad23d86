#include "geometry/tri_mesh.hpp"

#include "core/error.hpp"

namespace forensim {
namespace {
void check_indices(const std::vector<Tri>& tris, std::size_t limit, const std::string& source,
                   const std::string& what) {
  for (std::size_t f = 0; f < tris.size(); ++f) {
    for (Index i : tris[f]) {
      if (i < 0 || static_cast<std::size_t>(i) >= limit) {
        throw InputError(source, what + " " + std::to_string(f),
                         "index " + std::to_string(i) + " is out of range (there are " + std::to_string(limit) + ")");
      }
    }
  }
}
}  // namespace

void TriMesh::validate(const std::string& source) const {
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (!positions[v].allFinite()) throw InputError(source, "vertex " + std::to_string(v), "position is not finite");
  }
  check_indices(triangles, positions.size(), source, "triangle");
  require_input(
      normals.empty() || normals.size() == positions.size(), source, "normals",
      "count " + std::to_string(normals.size()) + " differs from vertex count " + std::to_string(positions.size()));
  for (std::size_t v = 0; v < normals.size(); ++v) {
    if (!normals[v].allFinite()) throw InputError(source, "normal " + std::to_string(v), "is not finite");
  }
  require_input(colors.empty() || colors.size() == positions.size(), source, "colors",
                "count differs from vertex count");
  require_input(triangle_uvs.empty() || triangle_uvs.size() == triangles.size(), source, "triangle UVs",
                "count differs from triangle count");
  check_indices(triangle_uvs, uvs.size(), source, "triangle UV");
  for (std::size_t i = 0; i < uvs.size(); ++i) {
    if (!uvs[i].allFinite()) throw InputError(source, "uv " + std::to_string(i), "is not finite");
  }
  require_input(triangle_labels.empty() || triangle_labels.size() == triangles.size(), source, "triangle labels",
                "count differs from triangle count");
  vertex_fields.validate(positions.size(), source, "vertices");
  triangle_fields.validate(triangles.size(), source, "triangles");
}

}  // namespace forensim
