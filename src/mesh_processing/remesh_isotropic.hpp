#pragma once
/// Isotropic remeshing: uniform, well-shaped triangles of a chosen size, for skins to be tetrahedralised
/// and simulated.

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Remeshes `mesh` towards edges of `target_edge_length_mm` by `iterations` rounds of edge splits,
/// collapses, flips and tangential relaxation with projection onto the input (Botsch and Kobbelt 2004,
/// CGAL::Polygon_mesh_processing::isotropic_remeshing). Borders of open meshes are first split to the
/// target length and then kept in place (protected). Interior vertices left with three edges (spikes on sharp
/// features, which a simulated skin snaps through) are removed, their three triangles merged. The input must be
/// a valid mesh (run repair_mesh() first on scans; non-manifold inputs are split by CGAL's orient_polygon_soup).
/// Per-vertex and per-triangle attributes (UVs, colours, labels, fields) are dropped because the vertices are
/// new; normals are recomputed and the material is kept. Throws InputError for a non-positive target length or a
/// negative iteration count.
TriMesh remesh_isotropic(const TriMesh& mesh, double target_edge_length_mm, int iterations = 3);

/// remesh_isotropic() to about `triangles` triangles: an equilateral triangle of edge L covers sqrt(3)/4 L^2, so L
/// follows from the surface area; when the count comes out more than 5 % off, one more pass from the input with
/// L corrected by sqrt(count / target) (the count goes as L^-2). Throws InputError for zero triangles or a mesh
/// without area.
TriMesh remesh_to_triangle_count(const TriMesh& mesh, std::size_t triangles, int iterations = 3);

}  // namespace forensim
