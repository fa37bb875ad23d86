#pragma once
/// Internal to the mesh_processing module (included only by its .cpp files; CGAL is a private dependency,
/// so no public header may include this one): conversions between forensim's TriMesh and
/// CGAL::Surface_mesh, and the hole filler shared by repair_mesh().

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <string>

#include "geometry/tri_mesh.hpp"

namespace forensim::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

/// What to_surface_mesh() had to change to make the triangles a valid halfedge mesh.
struct ConversionStats {
  std::size_t degenerate_triangles_dropped = 0;  ///< triangles repeating a vertex index
  std::size_t vertices_duplicated = 0;           ///< copies made to separate non-manifold vertices and edges
  std::size_t triangles_flipped = 0;             ///< flipped to orient the soup consistently
};

/// Builds a Surface_mesh from positions and triangles (other attributes are ignored). Triangles repeating a
/// vertex are dropped. If the triangles do not form a valid oriented 2-manifold-with-boundary,
/// CGAL::Polygon_mesh_processing::orient_polygon_soup() first makes them one (flipping triangles and
/// duplicating vertices at non-manifold places), as counted in `stats`.
SurfaceMesh to_surface_mesh(const TriMesh& mesh, ConversionStats* stats = nullptr);

/// Positions and triangles of a Surface_mesh (removed elements skipped, vertices renumbered in order).
/// Faces with more than three sides are fan-triangulated. Normals, UVs, colours and fields are empty.
TriMesh to_tri_mesh(const SurfaceMesh& mesh);

/// Options and results of fill_holes().
struct HoleFilling {
  std::size_t max_edges = 0;  ///< holes with more boundary edges are skipped (0 = no limit)
  double max_diameter = 0.0;  ///< holes whose boundary's bounding-box diagonal is larger are skipped (0 = no limit)
  bool refine = true;         ///< add interior vertices to match the density around the hole
  bool fair = true;           ///< fair the patch (Liepa 2003; needs refine)

  std::size_t holes_found = 0;
  std::size_t holes_filled = 0;
  std::size_t holes_skipped = 0;   ///< too large for max_edges / max_diameter
  std::size_t holes_failed = 0;    ///< CGAL found no triangulation
  std::size_t fairing_failed = 0;  ///< filled and refined but not faired
  std::size_t triangles_added = 0;
};

/// Fills the holes of `mesh` (triangulate, optionally refine and fair) within the size limits in `options`,
/// counting what was done in the same struct.
void fill_holes(SurfaceMesh& mesh, HoleFilling& options);

}  // namespace forensim::cgal
