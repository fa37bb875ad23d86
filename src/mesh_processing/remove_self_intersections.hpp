#pragma once
/// Removal of self-intersections from a closed triangle mesh, as scans have them where thin parts press
/// together (closed lips, eyelids, ear folds): the triangles that pass through others are removed with a
/// neighbourhood and the holes refilled with smooth patches, repeated until none cross (CGAL Polygon Mesh
/// Processing, experimental::remove_self_intersections). The tet mesher needs embedded surfaces.

#include <cstddef>
#include <string>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// What remove_self_intersections() did.
struct SelfIntersectionRepair {
  std::size_t intersecting_pairs_before = 0;  ///< pairs of triangles that cross (CGAL self_intersections)
  std::size_t intersecting_pairs_after = 0;
  std::size_t triangles_before = 0, triangles_after = 0;
  bool embedded() const { return intersecting_pairs_after == 0; }
};

/// Removes the self-intersections of `mesh` in place (positions and triangles; other attributes are dropped
/// when anything changes). A mesh without self-intersections is left as it is. Throws InputError naming
/// `name` for an invalid mesh.
SelfIntersectionRepair remove_self_intersections(TriMesh& mesh, const std::string& name);

}  // namespace forensim
