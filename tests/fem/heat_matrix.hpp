#pragma once
// Test helper shared by the fem solver tests: an SPD system of the kind the moisture step solves.

#include "fem/sparse_assembly.hpp"
#include "fem/tet_element.hpp"
#include "geometry/tet_mesh.hpp"

namespace forensim::test {

/// Consistent mass + scale * Laplacian of `mesh` (SPD), assembled into `pattern` (full symmetric storage).
inline SparseMatrix heat_matrix(const TetMesh& mesh, const SparsityPattern& pattern, double scale) {
  SparseMatrix a = pattern.make_matrix();
  pattern.assemble_scalar(
      [&](std::size_t e, Mat4& m) {
        const Tet& t = mesh.tets[e];
        const TetCorners p{mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]};
        double volume = 0.0;
        const Mat34 g = tet_shape_gradients(p, &volume);
        m = tet_diffusion_stiffness(g, volume, scale) + tet_consistent_mass(volume, 1.0);
      },
      a);
  return a;
}

}  // namespace forensim::test
