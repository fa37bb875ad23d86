#pragma once
/// One call to export a surface mesh in the format its file name asks for.

#include <filesystem>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Writes `mesh` (millimetres) by extension, case-insensitive: .obj (write_obj, with .mtl), .ply (binary
/// write_ply), .stl (write_stl), .glb / .gltf (write_gltf: converted to metres, textures named in the
/// material embedded). Throws InputError for other extensions or an invalid mesh, IoError on write failure.
void write_mesh(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace forensim
