#pragma once
/// UV seams of a triangle mesh: edges shared by two triangles that give the edge's vertices different texture
/// coordinates, so the surface is continuous there but its texture is not. A wound painted across one is where
/// distances in UV space (the thesis's way) break and distances on the surface do not.

#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// One seam edge.
struct UvSeamEdge {
  Vec3 midpoint;    ///< midpoint of the edge on the surface (mesh units)
  Vec2 uv_a, uv_b;  ///< the midpoint's UV in either triangle, moved 2% towards that triangle's third corner
  std::size_t triangle_a = 0, triangle_b = 0;  ///< the two triangles
};

/// Seam edges of `mesh` (with UVs; none otherwise): edges whose two triangles' UVs at the edge's midpoint
/// differ by more than `tolerance` in UV units.
std::vector<UvSeamEdge> uv_seam_edges(const TriMesh& mesh, double tolerance = 1e-3);

}  // namespace forensim
