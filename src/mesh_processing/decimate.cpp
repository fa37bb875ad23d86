// CGAL's Garland-Heckbert quadrics are Eigen 4x4 matrices that GCC believes may be used uninitialised
// (a false positive inside Eigen's storage, reached through CGAL); silenced for this file only.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "mesh_processing/decimate.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"  // false positives inside CGAL's containers
// number_utils.h must come first: Bounded_normal_change_placement.h calls is_positive without including it.
#include <CGAL/number_utils.h>

#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#pragma GCC diagnostic pop

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "mesh_processing/cgal_surface_mesh.hpp"

namespace forensim {

namespace SMS = CGAL::Surface_mesh_simplification;

namespace {

/// Stops once the live face count reaches the target (CGAL's Count_stop_predicate counts edges).
struct FaceCountStop {
  const cgal::SurfaceMesh* mesh;
  std::size_t target;

  template <typename Cost, typename Profile>
  bool operator()(const Cost& /*cost*/, const Profile& /*profile*/, std::size_t /*initial_edges*/,
                  std::size_t /*current_edges*/) const {
    return mesh->number_of_faces() <= target;
  }
};

}  // namespace

TriMesh decimate(const TriMesh& mesh, std::size_t target_triangles) {
  mesh.validate("mesh to decimate");
  require_input(target_triangles > 0, "decimation", "target_triangles", "must be at least 1");
  cgal::SurfaceMesh sm = cgal::to_surface_mesh(mesh);
  if (sm.number_of_faces() > target_triangles) {
    using Policies = SMS::GarlandHeckbert_plane_policies<cgal::SurfaceMesh, cgal::Kernel>;
    Policies policies(sm);
    const SMS::Bounded_normal_change_placement<Policies::Get_placement> placement(policies.get_placement());
    SMS::edge_collapse(sm, FaceCountStop{&sm, target_triangles},
                       CGAL::parameters::get_cost(policies.get_cost()).get_placement(placement));
    sm.collect_garbage();
  }
  TriMesh result = cgal::to_tri_mesh(sm);
  result.material = mesh.material;
  compute_normals(result);
  return result;
}

}  // namespace forensim
