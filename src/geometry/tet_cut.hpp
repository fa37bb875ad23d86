#pragma once
/// Cut-aways of tet meshes: the tets on one side of a plane, for pictures that show the inside of a body.

#include "core/types.hpp"
#include "geometry/tet_mesh.hpp"

namespace forensim {

/// The tets of `mesh` whose centroid lies on or behind the plane through `point` with normal `normal` ((c -
/// point) . normal <= 0; the side the normal points to is removed), with their labels. All nodes are kept
/// (positions unchanged), so node-indexed data still applies. Throws InputError for a zero normal.
TetMesh tets_behind_plane(const TetMesh& mesh, const Vec3& point, const Vec3& normal);

}  // namespace forensim
