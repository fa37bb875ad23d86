#include "mesh_processing/remesh_isotropic.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"  // false positives inside CGAL's containers
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#pragma GCC diagnostic pop

#include <array>
#include <boost/iterator/function_output_iterator.hpp>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "mesh_processing/cgal_surface_mesh.hpp"

namespace forensim {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

/// Removes interior vertices with three edges (CGAL::Euler::remove_center_vertex: their three triangles become
/// one). Isotropic remeshing leaves a few on sharp features, often as spikes standing off their neighbours'
/// triangle; held only by bending, they snap through it under a simulated skin's compression. Passes repeat while
/// a removal leaves a new one; a vertex next to another of three edges, or one whose fan closes a tetrahedron (the
/// same face across all three rims), is kept.
void remove_valence_three_vertices(cgal::SurfaceMesh& sm) {
  using Face = cgal::SurfaceMesh::Face_index;
  for (int pass = 0; pass < 8; ++pass) {
    bool removed = false;
    for (const auto v : sm.vertices()) {
      if (sm.is_border(v) || sm.degree(v) != 3) continue;
      const auto h = sm.halfedge(v);  // a halfedge pointing to v
      bool keep = false;
      std::array<Face, 3> across{};
      int k = 0;
      for (const auto g : CGAL::halfedges_around_target(h, sm)) {
        // The face across the fan's rim edge (opposite v in g's face).
        across[static_cast<std::size_t>(k++)] = sm.face(sm.opposite(sm.next(g)));
        keep = keep || sm.degree(sm.source(g)) <= 3;
      }
      keep = keep || across[0] == across[1] || across[1] == across[2] || across[0] == across[2];
      if (keep) continue;
      CGAL::Euler::remove_center_vertex(h, sm);
      removed = true;
    }
    if (!removed) break;
  }
}

}  // namespace

TriMesh remesh_isotropic(const TriMesh& mesh, double target_edge_length_mm, int iterations) {
  mesh.validate("mesh to remesh");
  require_input(std::isfinite(target_edge_length_mm) && target_edge_length_mm > 0.0, "remeshing",
                "target_edge_length_mm", "must be positive, got " + std::to_string(target_edge_length_mm));
  require_input(iterations >= 0, "remeshing", "iterations", "must be >= 0, got " + std::to_string(iterations));
  cgal::SurfaceMesh sm = cgal::to_surface_mesh(mesh);
  if (sm.number_of_faces() > 0) {
    using Edge = cgal::SurfaceMesh::Edge_index;
    std::vector<Edge> border;
    PMP::border_halfedges(faces(sm), sm, boost::make_function_output_iterator([&](cgal::SurfaceMesh::Halfedge_index h) {
                            border.push_back(sm.edge(h));
                          }));
    // Borders are split to the target first so that protecting them does not leave long edges behind.
    PMP::split_long_edges(border, target_edge_length_mm, sm);
    PMP::isotropic_remeshing(
        faces(sm), target_edge_length_mm, sm,
        CGAL::parameters::number_of_iterations(static_cast<unsigned>(iterations)).protect_constraints(true));
    remove_valence_three_vertices(sm);
    sm.collect_garbage();
  }
  TriMesh result = cgal::to_tri_mesh(sm);
  result.material = mesh.material;
  compute_normals(result);
  return result;
}

TriMesh remesh_to_triangle_count(const TriMesh& mesh, std::size_t triangles, int iterations) {
  require_input(triangles > 0, "remesh", "triangle count", "must be positive");
  const double area = surface_area(mesh);
  require_input(std::isfinite(area) && area > 0.0, "remesh", "mesh", "has no area");
  const double target = static_cast<double>(triangles);
  const double edge = std::sqrt(4.0 * area / (std::sqrt(3.0) * target));
  TriMesh result = remesh_isotropic(mesh, edge, iterations);
  const double got = static_cast<double>(result.triangle_count());
  if (std::abs(got - target) > 0.05 * target)
    result = remesh_isotropic(mesh, edge * std::sqrt(got / target), iterations);
  return result;
}

}  // namespace forensim
