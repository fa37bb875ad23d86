#pragma once
/// OpenVDB's level-set mesher output (tools::volumeToMesh: triangles and quads) as a triangle mesh. Internal to
/// the volume module, which links OpenVDB privately: include it from its .cpp files only.

#include <openvdb/openvdb.h>

#include <vector>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// A triangle mesh on `positions` (mm; the mesher's points already mapped to the output frame, one per point)
/// from the mesher's triangles and quads. Each quad is split along its shorter diagonal (in `positions`), and
/// every polygon's winding is reversed when `reverse` is true. No normals are computed.
TriMesh mesh_from_vdb_polygons(std::vector<Vec3> positions, const std::vector<openvdb::Vec3I>& triangles,
                               const std::vector<openvdb::Vec4I>& quads, bool reverse);

}  // namespace forensim
