#include "mesh_processing/repair_mesh.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"  // false positives inside CGAL's containers
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#pragma GCC diagnostic pop

#include <array>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "mesh_processing/cgal_surface_mesh.hpp"

namespace forensim {

namespace PMP = CGAL::Polygon_mesh_processing;
using cgal::Point;
using cgal::SurfaceMesh;

namespace {

using Polygon = std::vector<std::size_t>;

std::size_t remove_index_degenerate(std::vector<Polygon>& polygons) {
  const std::size_t before = polygons.size();
  std::erase_if(polygons, [](const Polygon& p) { return p[0] == p[1] || p[1] == p[2] || p[0] == p[2]; });
  return before - polygons.size();
}

/// Corner positions of every face, to find faces whose orientation an operation reversed.
std::vector<std::array<Point, 3>> face_corners(const SurfaceMesh& mesh) {
  std::vector<std::array<Point, 3>> corners(mesh.num_faces());
  for (const SurfaceMesh::Face_index f : mesh.faces()) {
    int k = 0;
    for (const SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k < 3) corners[f.idx()][k] = mesh.point(v);
      ++k;
    }
  }
  return corners;
}

void toggle_reversed(const SurfaceMesh& mesh, const std::vector<std::array<Point, 3>>& before,
                     SurfaceMesh::Property_map<SurfaceMesh::Face_index, bool>& flipped) {
  const auto after = face_corners(mesh);
  for (const SurfaceMesh::Face_index f : mesh.faces()) {
    const auto& a = before[f.idx()];
    const auto& b = after[f.idx()];
    // Same cyclic order means same orientation.
    const bool same =
        (a[0] == b[0] && a[1] == b[1]) || (a[0] == b[1] && a[1] == b[2]) || (a[0] == b[2] && a[1] == b[0]);
    if (!same) flipped[f] = !flipped[f];
  }
}

}  // namespace

std::string RepairReport::summary() const {
  std::ostringstream out;
  out << "before: " << before.summary() << "\n";
  out << "after:  " << after.summary() << "\n";
  out << "merged " << vertices_merged << " vertices; removed " << degenerate_triangles_removed << " degenerate and "
      << duplicate_triangles_removed << " duplicate triangles and " << isolated_vertices_removed
      << " isolated vertices; flipped " << triangles_flipped << " triangles; split " << vertices_split_nonmanifold
      << " non-manifold vertices; stitched " << edges_stitched << " edges\n";
  out << "holes: " << holes_found << " found, " << holes_filled << " filled (" << triangles_added << " triangles), "
      << holes_skipped << " left open as too large, " << holes_failed << " failed";
  if (self_intersections_checked) out << "\nself-intersections: " << (self_intersecting ? "yes" : "none");
  for (const std::string& note : notes) out << "\nnote: " << note;
  return out.str();
}

RepairReport repair_mesh(TriMesh& mesh, const RepairOptions& options) {
  mesh.validate("mesh to repair");
  require_input(options.merge_distance >= 0.0, "repair options", "merge_distance", "must be >= 0");
  require_input(options.max_hole_diameter >= 0.0, "repair options", "max_hole_diameter", "must be >= 0");
  RepairReport report;
  report.before = check_topology(mesh);

  TriMesh work;
  work.positions = mesh.positions;
  work.triangles = mesh.triangles;
  if (options.merge_distance > 0.0) {
    const std::size_t vertices = work.vertex_count();
    const std::size_t triangles = work.triangle_count();
    work = weld_vertices(work, options.merge_distance);
    report.vertices_merged += vertices - work.vertex_count();
    report.degenerate_triangles_removed += triangles - work.triangle_count();
  }

  // Polygon soup stage: duplicates, degenerate and isolated elements, consistent orientation.
  std::vector<Point> points;
  points.reserve(work.positions.size());
  for (const Vec3& p : work.positions) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<Polygon> polygons;
  polygons.reserve(work.triangles.size());
  for (const Tri& t : work.triangles) {
    polygons.push_back(
        {static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
  }
  work = TriMesh{};
  report.vertices_merged += PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  report.degenerate_triangles_removed += remove_index_degenerate(polygons);
  report.duplicate_triangles_removed += PMP::merge_duplicate_polygons_in_polygon_soup(points, polygons);
  report.isolated_vertices_removed += PMP::remove_isolated_points_in_polygon_soup(points, polygons);
  std::vector<bool> soup_flipped;
  {
    const std::size_t point_count = points.size();
    const std::vector<Polygon> original = polygons;
    if (!PMP::orient_polygon_soup(points, polygons)) {
      report.notes.push_back("the triangles could not be oriented consistently without splitting the mesh apart at " +
                             std::to_string(points.size() - point_count) + " duplicated vertices");
    }
    report.vertices_split_nonmanifold += points.size() - point_count;
    soup_flipped.resize(polygons.size());
    for (std::size_t i = 0; i < polygons.size(); ++i) {
      soup_flipped[i] =
          points[polygons[i][0]] != points[original[i][0]] || points[polygons[i][1]] != points[original[i][1]];
    }
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  points.clear();
  polygons.clear();
  // Net orientation change of every face against the input (faces are created in polygon order; the map
  // follows them through garbage collection; faces added later start unflipped).
  auto flipped = sm.add_property_map<SurfaceMesh::Face_index, bool>("f:forensim_flipped", false).first;
  for (const SurfaceMesh::Face_index f : sm.faces()) flipped[f] = soup_flipped[f.idx()];

  // Halfedge mesh stage.
  report.edges_stitched += PMP::stitch_borders(sm);
  {
    const std::size_t faces = sm.number_of_faces();
    if (!PMP::remove_degenerate_faces(sm)) report.notes.push_back("some zero-area triangles could not be removed");
    sm.collect_garbage();
    if (sm.number_of_faces() < faces) report.degenerate_triangles_removed += faces - sm.number_of_faces();
  }
  report.vertices_split_nonmanifold += PMP::duplicate_non_manifold_vertices(sm);

  if (options.fill_holes) {
    cgal::HoleFilling filling;
    filling.max_edges = options.max_hole_edges;
    filling.max_diameter = options.max_hole_diameter;
    filling.refine = options.refine_holes;
    filling.fair = options.fair_holes && options.refine_holes;
    cgal::fill_holes(sm, filling);
    report.holes_found = filling.holes_found;
    report.holes_filled = filling.holes_filled;
    report.holes_skipped = filling.holes_skipped;
    report.holes_failed = filling.holes_failed;
    report.triangles_added = filling.triangles_added;
    if (filling.fairing_failed > 0) {
      report.notes.push_back(std::to_string(filling.fairing_failed) + " filled holes could not be faired (left flat)");
    }
  }

  if (options.orient_outward && CGAL::is_closed(sm) && sm.number_of_faces() > 0) {
    const auto corners = face_corners(sm);
    PMP::orient_to_bound_a_volume(sm);
    toggle_reversed(sm, corners, flipped);
  } else if (options.orient_outward && sm.number_of_faces() > 0) {
    report.notes.push_back("the mesh is open, so it was oriented consistently but not necessarily outward");
  }
  if (options.check_self_intersections) {
    report.self_intersections_checked = true;
    report.self_intersecting = PMP::does_self_intersect(sm);
    if (report.self_intersecting) report.notes.push_back("the surface intersects itself (not repaired)");
  }
  report.isolated_vertices_removed += PMP::remove_isolated_vertices(sm);
  sm.collect_garbage();

  for (const SurfaceMesh::Face_index f : sm.faces()) report.triangles_flipped += flipped[f] ? 1 : 0;

  TriMesh result = cgal::to_tri_mesh(sm);
  result.material = mesh.material;
  compute_normals(result);
  mesh = std::move(result);
  report.after = check_topology(mesh);
  if (!report.after.is_manifold()) {
    report.notes.push_back(std::to_string(report.after.nonmanifold_edge_count) + " non-manifold edges and " +
                           std::to_string(report.after.nonmanifold_vertex_count) + " non-manifold vertices remain");
  }
  if (report.after.boundary_loop_count > 0) {
    report.notes.push_back(std::to_string(report.after.boundary_loop_count) + " holes remain open");
  }
  return report;
}

}  // namespace forensim
