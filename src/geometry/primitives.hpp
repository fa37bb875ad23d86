#pragma once
/// Simple closed shapes: analytic test cases for every module (areas, volumes, diffusion, elasticity).

#include "core/types.hpp"
#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Closed, outward-oriented box surface from `min` to `max`, each face split into n x n quads of two
/// triangles, welded along the box edges (6 n^2 + 2 vertices, 12 n^2 triangles).
TriMesh make_box_mesh(const Vec3& min, const Vec3& max, int n = 1);

/// Closed, outward-oriented icosphere: an icosahedron subdivided `subdivisions` times, projected on the sphere.
TriMesh make_icosphere(const Vec3& center, double radius, int subdivisions);

/// Box filled with nx*ny*nz cubes, each cut into 6 positively oriented tets along its main diagonal
/// (Freudenthal/Kuhn subdivision, conforming across cubes).
TetMesh make_box_tet_mesh(const Vec3& min, const Vec3& max, int nx, int ny, int nz);

}  // namespace forensim
