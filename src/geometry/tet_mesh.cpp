#include "geometry/tet_mesh.hpp"

#include "core/error.hpp"

namespace forensim {

void TetMesh::validate(const std::string& source) const {
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (!positions[v].allFinite()) throw InputError(source, "node " + std::to_string(v), "position is not finite");
  }
  for (std::size_t t = 0; t < tets.size(); ++t) {
    for (Index i : tets[t]) {
      if (i < 0 || static_cast<std::size_t>(i) >= positions.size()) {
        throw InputError(source, "tet " + std::to_string(t),
                         "node index " + std::to_string(i) + " is out of range (there are " +
                             std::to_string(positions.size()) + " nodes)");
      }
    }
    const Tet& k = tets[t];
    if (k[0] == k[1] || k[0] == k[2] || k[0] == k[3] || k[1] == k[2] || k[1] == k[3] || k[2] == k[3])
      throw InputError(source, "tet " + std::to_string(t), "repeats a node");
  }
  require_input(
      tet_labels.empty() || tet_labels.size() == tets.size(), source, "tet labels",
      "count " + std::to_string(tet_labels.size()) + " differs from tet count " + std::to_string(tets.size()));
  vertex_fields.validate(positions.size(), source, "nodes");
  tet_fields.validate(tets.size(), source, "tets");
}

}  // namespace forensim
