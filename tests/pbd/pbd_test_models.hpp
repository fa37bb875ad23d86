#pragma once
/// Body models for the skin tests, built without the tetrahedraliser: a ball of tets (a box grid pushed onto the
/// ball) under a finer icosphere skin, and volume motions (shrinking, translation) to drive the skin with.

#include <cmath>
#include <vector>

#include "body/body_model.hpp"
#include "core/types.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_mesh.hpp"

namespace forensim::test {

/// make_box_tet_mesh(-r..r, n^3 cubes) with every node pushed radially onto the ball of radius r.
inline TetMesh make_ball_volume(double r, int n) {
  TetMesh mesh = make_box_tet_mesh(Vec3::Constant(-r), Vec3::Constant(r), n, n, n);
  for (Vec3& p : mesh.positions) {
    const double norm = p.norm();
    if (norm > 0.0) p *= p.cwiseAbs().maxCoeff() / norm;
  }
  return mesh;
}

/// A ball volume of radius 10 mm (6^3 cells) under an icosphere skin of radius 10.1 mm (3 subdivisions:
/// 642 vertices, 1280 triangles).
inline BodyModel sphere_body() {
  return make_body_model(make_ball_volume(10.0, 6), make_icosphere(Vec3::Zero(), 10.1, 3));
}

/// A flat sheet in the xy plane: (nx + 1) x (ny + 1) vertices `spacing` mm apart from the origin, two triangles per
/// cell (normals +z).
inline TriMesh make_grid_sheet(int nx, int ny, double spacing) {
  TriMesh sheet;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) sheet.positions.emplace_back(spacing * i, spacing * j, 0.0);
  auto id = [&](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      sheet.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      sheet.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return sheet;
}

/// The volume's nodes scaled about the origin by `factor` (a uniformly shrinking ball for factor < 1).
inline std::vector<Vec3> scaled_nodes(const TetMesh& volume, double factor) {
  std::vector<Vec3> out = volume.positions;
  for (Vec3& p : out) p *= factor;
  return out;
}

}  // namespace forensim::test
