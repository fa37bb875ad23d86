#pragma once
/// Volumes and skins for the body tests, built without the tetrahedraliser: box grids, a box grid mapped
/// onto a ball, and a box grid restricted to a phantom's inside.

#include <cmath>
#include <vector>

#include "body/body_model.hpp"
#include "core/types.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_mesh.hpp"
#include "phantoms/phantom.hpp"

namespace forensim::test {

/// make_box_tet_mesh(-r..r, n^3 cubes) with every node pushed radially onto the ball of radius r
/// (p -> p * |p|_inf / |p|_2): a sphere-like volume whose boundary nodes lie on the sphere.
inline TetMesh make_ball_tet_mesh(double r, int n) {
  TetMesh mesh = make_box_tet_mesh(Vec3::Constant(-r), Vec3::Constant(r), n, n, n);
  for (Vec3& p : mesh.positions) {
    const double norm = p.norm();
    if (norm > 0.0) p *= p.cwiseAbs().maxCoeff() / norm;
  }
  return mesh;
}

/// Smallest signed tet volume of a mesh (positive when every tet is positively oriented).
inline double min_tet_volume(const TetMesh& mesh) {
  double v = INFINITY;
  for (const Tet& t : mesh.tets)
    v = std::min(
        v, tet_signed_volume(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]));
  return v;
}

/// The cubes (edge `h` mm) of a grid over the phantom's bounds whose centre lies inside the skin, each cut
/// into 6 tets, with unused nodes removed. Its boundary lies within a cube diagonal of the skin.
inline TetMesh make_inside_cube_volume(const Phantom& phantom, double h) {
  const BoundingBox box = phantom.bounds();
  const Vec3 size = box.size();
  const int nx = static_cast<int>(std::ceil(size.x() / h)), ny = static_cast<int>(std::ceil(size.y() / h)),
            nz = static_cast<int>(std::ceil(size.z() / h));
  const Vec3 max = box.min + h * Vec3(nx, ny, nz);
  const TetMesh grid = make_box_tet_mesh(box.min, max, nx, ny, nz);
  TetMesh out;
  std::vector<Index> remap(grid.positions.size(), -1);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Vec3 centre = box.min + h * Vec3(i + 0.5, j + 0.5, k + 0.5);
        if (!(phantom.skin_distance(centre) < 0.0)) continue;
        const std::size_t first = 6 * ((static_cast<std::size_t>(k) * ny + j) * nx + i);
        for (std::size_t s = first; s < first + 6; ++s) {
          Tet t = grid.tets[s];
          for (Index& v : t) {
            if (remap[v] < 0) {
              remap[v] = static_cast<Index>(out.positions.size());
              out.positions.push_back(grid.positions[v]);
            }
            v = remap[v];
          }
          out.tets.push_back(t);
        }
      }
  return out;
}

/// A 10 mm box volume (3^3 cells, every seventh tet bone) under a skin box 0.2 mm larger, with two parts split
/// at x = 5.
inline BodyModel box_model() {
  TetMesh volume = make_box_tet_mesh(Vec3::Zero(), Vec3::Constant(10.0), 3, 3, 3);
  for (std::size_t t = 0; t < volume.tets.size(); ++t)
    volume.tet_labels.push_back(t % 7 == 0 ? tissue_bone : tissue_flesh);
  TriMesh skin = make_box_mesh(Vec3::Constant(-0.2), Vec3::Constant(10.2), 6);
  return make_body_model(std::move(volume), std::move(skin), {"left", "right"},
                         [](const Vec3& p) { return p.x() < 5.0 ? 0 : 1; });
}

}  // namespace forensim::test
