#pragma once
/// Repair of scanned and imported triangle meshes (hands, heads, skulls arrive open, with holes, duplicates
/// and inconsistent orientation) on CGAL Polygon Mesh Processing, with a report of what was done.

#include <limits>
#include <string>
#include <vector>

#include "geometry/mesh_topology.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

struct RepairOptions {
  /// Vertices closer than this (mm) are welded first (weld_vertices()); 0 merges exact duplicates only.
  double merge_distance = 0.0;
  bool fill_holes = true;
  /// Holes with more boundary edges than this are left open (0 = no limit). Large openings of a scan (the
  /// neck of a bust) are usually meant to stay open, and very large holes are slow to triangulate.
  std::size_t max_hole_edges = 500;
  /// Holes whose boundary's bounding-box diagonal exceeds this (mm) are left open (0 = no limit).
  double max_hole_diameter = 0.0;
  bool refine_holes = true;  ///< add vertices inside filled holes to match the surrounding density
  bool fair_holes = true;    ///< smooth filled holes (curvature-continuous fairing, Liepa 2003)
  /// Orient closed meshes so they bound a volume with outward normals (nested shells alternate).
  bool orient_outward = true;
  /// Also test for self-intersections (O(#F log #F); reported, not repaired).
  bool check_self_intersections = false;
};

/// What repair_mesh() did, and the state of the result.
struct RepairReport {
  TopologyReport before;  ///< topology of the input
  TopologyReport after;   ///< topology of the result

  std::size_t vertices_merged = 0;               ///< welded or exact duplicates merged
  std::size_t degenerate_triangles_removed = 0;  ///< repeated vertex index or zero area
  std::size_t duplicate_triangles_removed = 0;   ///< same three vertices (in either orientation)
  std::size_t isolated_vertices_removed = 0;
  std::size_t triangles_flipped = 0;           ///< to make orientation consistent, or outward
  std::size_t vertices_split_nonmanifold = 0;  ///< copies made to separate non-manifold vertices/edges
  std::size_t edges_stitched = 0;              ///< pairs of coincident border edges joined
  std::size_t holes_found = 0;
  std::size_t holes_filled = 0;
  std::size_t holes_skipped = 0;    ///< above max_hole_edges / max_hole_diameter
  std::size_t holes_failed = 0;     ///< no triangulation found
  std::size_t triangles_added = 0;  ///< by hole filling
  bool self_intersections_checked = false;
  bool self_intersecting = false;  ///< only meaningful when checked
  std::vector<std::string> notes;  ///< problems that remain, in words

  bool closed() const { return after.is_closed(); }
  bool manifold() const { return after.is_manifold(); }
  /// Several lines: counts of what was done, the topology before and after, and the notes.
  std::string summary() const;
};

/// Repairs `mesh` in place: welds vertices closer than options.merge_distance, removes triangles that
/// repeat a vertex, duplicate triangles and isolated vertices (CGAL repair_polygon_soup steps), orients the
/// triangles consistently (orient_polygon_soup, splitting non-manifold vertices and edges where no
/// consistent orientation exists), stitches coincident borders (stitch_borders), removes zero-area
/// triangles (remove_degenerate_faces), splits remaining non-manifold vertices
/// (duplicate_non_manifold_vertices), fills holes within the size limits (triangulate, refine, fair), and
/// orients closed meshes outward (orient_to_bound_a_volume). Only positions and triangles survive: UVs,
/// colours, labels and fields are dropped (vertices are renumbered and added), normals are recomputed; the
/// material is kept. Non-manifold edges that CGAL cannot repair are reported in `notes`.
RepairReport repair_mesh(TriMesh& mesh, const RepairOptions& options = {});

}  // namespace forensim
