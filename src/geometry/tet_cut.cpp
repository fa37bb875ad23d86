#include "geometry/tet_cut.hpp"

#include "core/error.hpp"

namespace forensim {

TetMesh tets_behind_plane(const TetMesh& mesh, const Vec3& point, const Vec3& normal) {
  require_input(normal.allFinite() && normal.norm() > 0.0, "cut plane", "normal", "must be a finite, non-zero vector");
  const Vec3 n = normal.normalized();
  TetMesh kept;
  kept.positions = mesh.positions;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    Vec3 c = Vec3::Zero();
    for (Index v : mesh.tets[t]) c += mesh.positions[static_cast<std::size_t>(v)] / 4.0;
    if ((c - point).dot(n) <= 0.0) {
      kept.tets.push_back(mesh.tets[t]);
      kept.tet_labels.push_back(mesh.label(t));
    }
  }
  return kept;
}

}  // namespace forensim
