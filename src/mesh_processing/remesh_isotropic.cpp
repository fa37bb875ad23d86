#include "mesh_processing/remesh_isotropic.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"  // false positives inside CGAL's containers
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#pragma GCC diagnostic pop

#include <boost/iterator/function_output_iterator.hpp>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "mesh_processing/cgal_surface_mesh.hpp"

namespace forensim {

namespace PMP = CGAL::Polygon_mesh_processing;

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
