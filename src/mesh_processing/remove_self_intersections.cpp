// False positives of -Wnull-dereference inside CGAL's triangulation containers after inlining (reported at
// header locations, so disabled before any include).
#pragma GCC diagnostic ignored "-Wnull-dereference"
// Likewise -Wmaybe-uninitialized in std::pair and CGAL's Polyhedral_envelope at -O1 (sanitizer builds).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "mesh_processing/remove_self_intersections.hpp"

#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <iterator>
#include <utility>
#include <vector>

#include "mesh_processing/cgal_surface_mesh.hpp"

namespace forensim {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

std::size_t intersecting_pairs(const cgal::SurfaceMesh& sm) {
  std::vector<std::pair<cgal::SurfaceMesh::Face_index, cgal::SurfaceMesh::Face_index>> pairs;
  PMP::self_intersections(sm, std::back_inserter(pairs));
  return pairs.size();
}

}  // namespace

SelfIntersectionRepair remove_self_intersections(TriMesh& mesh, const std::string& name) {
  mesh.validate(name);
  SelfIntersectionRepair report;
  report.triangles_before = report.triangles_after = mesh.triangle_count();
  cgal::SurfaceMesh sm = cgal::to_surface_mesh(mesh);
  report.intersecting_pairs_before = report.intersecting_pairs_after = intersecting_pairs(sm);
  if (report.intersecting_pairs_before == 0) return report;
  // The genus may change (a fold pressed through itself becomes a handle or loses one): what matters is an
  // embedded surface bounding the same region.
  PMP::experimental::remove_self_intersections(sm, CGAL::parameters::preserve_genus(false));
  sm.collect_garbage();
  report.intersecting_pairs_after = intersecting_pairs(sm);
  TriMesh result = cgal::to_tri_mesh(sm);
  result.material = mesh.material;
  report.triangles_after = result.triangle_count();
  mesh = std::move(result);
  return report;
}

}  // namespace forensim
