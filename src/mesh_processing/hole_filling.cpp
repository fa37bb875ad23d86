// Hole filling for repair_mesh(): triangulation (Liepa 2003 / Barequet and Sharir 1995 as implemented by
// CGAL PMP), refinement and fairing. Kept in its own file because of its compile cost.
#define CGAL_EIGEN3_ENABLED 1

// GCC's optimiser reports possible null dereferences inside CGAL's containers (false positives in
// third-party code); silence them for the CGAL headers only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#pragma GCC diagnostic pop

#include <iterator>
#include <limits>
#include <vector>

#include "mesh_processing/cgal_surface_mesh.hpp"

namespace forensim::cgal {

namespace PMP = CGAL::Polygon_mesh_processing;

void fill_holes(SurfaceMesh& mesh, HoleFilling& options) {
  using Halfedge = SurfaceMesh::Halfedge_index;
  std::vector<Halfedge> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  options.holes_found += cycles.size();
  for (const Halfedge h : cycles) {
    if (!mesh.is_border(h)) continue;  // an earlier fill closed it
    std::size_t edges = 0;
    CGAL::Bbox_3 box;
    for (const Halfedge e : CGAL::halfedges_around_face(h, mesh)) {
      ++edges;
      box += mesh.point(mesh.target(e)).bbox();
    }
    const double diameter = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                      CGAL::square(box.zmax() - box.zmin()));
    if ((options.max_edges > 0 && edges > options.max_edges) ||
        (options.max_diameter > 0.0 && diameter > options.max_diameter)) {
      ++options.holes_skipped;
      continue;
    }
    std::vector<SurfaceMesh::Face_index> faces;
    std::vector<SurfaceMesh::Vertex_index> vertices;
    const auto np = CGAL::parameters::use_2d_constrained_delaunay_triangulation(true).use_delaunay_triangulation(true);
    if (options.refine && options.fair) {
      const bool faired = std::get<0>(
          PMP::triangulate_refine_and_fair_hole(mesh, h, std::back_inserter(faces), std::back_inserter(vertices), np));
      if (!faired && !faces.empty()) ++options.fairing_failed;
    } else if (options.refine) {
      PMP::triangulate_and_refine_hole(mesh, h, std::back_inserter(faces), std::back_inserter(vertices), np);
    } else {
      PMP::triangulate_hole(mesh, h, std::back_inserter(faces), np);
    }
    if (faces.empty()) {
      ++options.holes_failed;
    } else {
      ++options.holes_filled;
      options.triangles_added += faces.size();
    }
  }
}

}  // namespace forensim::cgal
