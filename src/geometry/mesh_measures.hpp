#pragma once
/// Areas, volumes and normals of triangle and tetrahedral meshes.

#include <vector>

#include "core/types.hpp"
#include "geometry/tet_mesh.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Area of triangle (a, b, c).
double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c);
/// Total surface area of a triangle mesh (mm^2 for a mesh in mm).
double surface_area(const TriMesh& mesh);
/// Signed enclosed volume by the divergence theorem: positive for a closed mesh with outward-facing
/// (counter-clockwise) triangles. Meaningful only for closed meshes.
double enclosed_volume(const TriMesh& mesh);
/// Signed volume of tet (a, b, c, d): positive when (b-a).dot((c-a).cross(d-a)) > 0.
double tet_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// Sum of signed tet volumes; with `label` >= 0 only the tets with that label.
double tet_mesh_volume(const TetMesh& mesh, int label = -1);
/// Unit face normals (zero for degenerate triangles).
std::vector<Vec3> face_normals(const TriMesh& mesh);
/// Angle-weighted unit vertex normals (Thuermer and Wuethrich 1998); zero for isolated vertices.
std::vector<Vec3> vertex_normals(const TriMesh& mesh);
/// Fills mesh.normals with vertex_normals(mesh).
void compute_normals(TriMesh& mesh);

}  // namespace forensim
