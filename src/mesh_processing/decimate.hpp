#pragma once
/// Decimation of dense scans (millions of triangles) to a working resolution.

#include <cstddef>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Reduces `mesh` to at most `target_triangles` triangles (exactly that many, or one fewer, unless
/// collapses run out first) by edge collapses ordered by the Garland-Heckbert quadric error (Garland and
/// Heckbert 1997, CGAL Surface_mesh_simplification GarlandHeckbert_plane_policies) with placements
/// rejected when they flip a triangle normal (Bounded_normal_change_placement). Borders are weighted so
/// open edges stay in place. Per-vertex and per-triangle attributes other than positions are dropped;
/// normals are recomputed and the material is kept. A target at or above the input's count returns the
/// mesh unchanged (with recomputed normals). Throws InputError for target_triangles == 0.
TriMesh decimate(const TriMesh& mesh, std::size_t target_triangles);

}  // namespace forensim
