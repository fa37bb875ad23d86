#pragma once
/// Topology of triangle meshes: edges, manifoldness and closedness, connected components, welding.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

/// What check_topology() found. A closed 2-manifold has no boundary or non-manifold edges and no
/// non-manifold vertices; it is consistently oriented when every interior edge is used once in each direction.
struct TopologyReport {
  std::size_t edge_count = 0;
  std::size_t boundary_edge_count = 0;        ///< edges with one triangle (holes)
  std::size_t nonmanifold_edge_count = 0;     ///< edges with more than two triangles
  std::size_t nonmanifold_vertex_count = 0;   ///< vertices whose triangle fan is not a single disc or half-disc
  std::size_t misoriented_edge_count = 0;     ///< interior edges traversed twice in the same direction
  std::size_t degenerate_triangle_count = 0;  ///< triangles that repeat a vertex index or have zero area
  std::size_t isolated_vertex_count = 0;      ///< vertices used by no triangle
  std::size_t component_count = 0;            ///< edge-connected components of triangles
  std::size_t boundary_loop_count = 0;        ///< closed loops of boundary edges

  bool is_manifold() const { return nonmanifold_edge_count == 0 && nonmanifold_vertex_count == 0; }
  bool is_closed() const { return boundary_edge_count == 0 && nonmanifold_edge_count == 0; }
  bool is_oriented() const { return misoriented_edge_count == 0; }
  /// One line such as "closed, manifold, oriented; 2 components" or "open (3 holes, 120 boundary edges)".
  std::string summary() const;
};

/// Examines edges and vertex fans of a triangle mesh.
TopologyReport check_topology(const TriMesh& mesh);

/// Unique undirected edges (smaller index first), sorted.
std::vector<std::array<Index, 2>> unique_edges(const std::vector<Tri>& triangles);

/// Component id per triangle (triangles sharing an edge are connected); ids are 0..count-1 ordered by
/// each component's lowest triangle index. Returns the number of components through `count`.
std::vector<int> triangle_components(const TriMesh& mesh, int* count = nullptr);

/// Keeps the component(s) with the largest area; `keep` = how many of the largest to keep.
TriMesh keep_largest_components(const TriMesh& mesh, int keep = 1);

/// Subset of a mesh by triangle mask, dropping unused vertices and carrying every attribute along.
TriMesh extract_triangles(const TriMesh& mesh, const std::vector<bool>& keep_triangle);

/// Merges vertices closer than `tolerance` (positions quantised on a grid of that size and merged with their
/// neighbours) and drops triangles that become degenerate. Per-vertex attributes of the first vertex win.
/// Returns the old-to-new vertex map through `remap` when not null.
TriMesh weld_vertices(const TriMesh& mesh, double tolerance, std::vector<Index>* remap = nullptr);

}  // namespace forensim
