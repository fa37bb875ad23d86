#include "mesh_processing/cgal_surface_mesh.hpp"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <unordered_map>
#include <vector>

namespace forensim::cgal {

namespace PMP = CGAL::Polygon_mesh_processing;

SurfaceMesh to_surface_mesh(const TriMesh& mesh, ConversionStats* stats) {
  ConversionStats local;
  std::vector<Point> points;
  points.reserve(mesh.positions.size());
  for (const Vec3& p : mesh.positions) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(mesh.triangles.size());
  for (const Tri& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++local.degenerate_triangles_dropped;
      continue;
    }
    polygons.push_back(
        {static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    const std::size_t before = points.size();
    const auto original = polygons;
    PMP::orient_polygon_soup(points, polygons);
    local.vertices_duplicated = points.size() - before;
    // orient_polygon_soup reverses polygons in place and may renumber corners to new copies of a point,
    // so compare corner positions.
    for (std::size_t i = 0; i < polygons.size(); ++i) {
      if (points[polygons[i][0]] != points[original[i][0]] || points[polygons[i][1]] != points[original[i][1]]) {
        ++local.triangles_flipped;
      }
    }
  }
  SurfaceMesh result;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, result);
  if (stats != nullptr) *stats = local;
  return result;
}

TriMesh to_tri_mesh(const SurfaceMesh& mesh) {
  TriMesh out;
  std::vector<Index> index(mesh.num_vertices(), -1);  // num_vertices() includes removed ones
  out.positions.reserve(mesh.number_of_vertices());
  for (const SurfaceMesh::Vertex_index v : mesh.vertices()) {
    index[v.idx()] = static_cast<Index>(out.positions.size());
    const Point& p = mesh.point(v);
    out.positions.emplace_back(p.x(), p.y(), p.z());
  }
  out.triangles.reserve(mesh.number_of_faces());
  std::vector<Index> corners;
  for (const SurfaceMesh::Face_index f : mesh.faces()) {
    corners.clear();
    for (const SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      corners.push_back(index[v.idx()]);
    }
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      out.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }
  return out;
}

}  // namespace forensim::cgal
