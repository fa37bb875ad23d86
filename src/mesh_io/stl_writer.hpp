#pragma once
/// Binary STL export, for 3D printing of skulls and reconstructions.

#include <filesystem>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Writes `mesh` as binary little-endian STL: an 80-byte header, the triangle count and, per triangle, the
/// unit face normal and three float corners (coordinates as stored, normally millimetres). UVs, normals,
/// colours and materials are dropped (STL has none). Written atomically. Throws IoError / InputError.
void write_stl(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace forensim
