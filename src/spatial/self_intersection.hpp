#pragma once
/// Self-intersections of a triangle mesh: edges that pass through a triangle they do not touch. Two triangles in
/// general position intersect exactly when an edge of one crosses the other, so every edge is cast as a segment
/// against the mesh's BVH (spatial/ray_caster.hpp) and each crossing of a triangle that shares no vertex with the
/// edge counts. Used to check a simulated skin (no skin triangle may pass through another).

#include <cstddef>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Number of (edge, triangle) crossings of `mesh` between an edge and a triangle sharing no vertex with it, each
/// unique edge once (a crossing pair of triangles typically counts twice: two edges of one through the other, or
/// one edge of each). Crossings within `relative_margin` of the edge's length from its ends are not counted (a
/// vertex lying on a triangle is a touch, not a crossing). 0 for a closed, embedded surface. Throws InputError for
/// an invalid mesh.
std::size_t self_intersection_count(const TriMesh& mesh, double relative_margin = 1e-6);

}  // namespace forensim
