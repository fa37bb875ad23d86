#pragma once
/// Measured properties of the skin of a `forensim mummify` run, reported in its facts: how close the skin clings
/// to the bones per body part ("the skin ... clings firmly to the body frame", Frerichs, Vidler and Gatzidis 2020,
/// section 2), and whether any skin triangle turned over or passes through another.

#include <vector>

#include "body/body_model.hpp"
#include "core/types.hpp"

namespace forensim::cli {

/// Mean distance (mm) from the skin vertices of each part (#part_names entries; body.skin_vertex_parts) at
/// `skin_positions` (#S) to the bone surface of the volume at `node_positions` (#V): the boundary of the bone tets.
/// Empty when the body has no parts or no bone; a part without skin vertices gets 0.
std::vector<double> part_bone_distance_mm(const BodyModel& body, const std::vector<Vec3>& skin_positions,
                                          const std::vector<Vec3>& node_positions);

/// Skin triangles whose normal at `positions` (#S) points against their rest normal (dot product <= 0): turned over.
std::size_t inverted_skin_triangles(const TriMesh& rest_skin, const std::vector<Vec3>& positions);

/// Crossings of the skin at `positions` through itself (spatial/self_intersection.hpp).
std::size_t skin_self_intersections(const TriMesh& rest_skin, const std::vector<Vec3>& positions);

}  // namespace forensim::cli
