#pragma once
/// Wavefront OBJ export, the lowest common denominator of Blender, Houdini, MeshLab and scanner software.

#include <filesystem>

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Writes `mesh` as OBJ (coordinates as stored, normally millimetres): `v` positions (with `r g b` vertex
/// colours when the mesh has them), `vn` per-vertex normals, `vt` corner UVs (v up), and `f v/vt/vn` faces.
/// Also writes `<stem>.mtl` beside it, referenced by `mtllib`, with the material's base colour (Kd), opacity
/// (d) and `map_Kd`/`norm`/`map_Pr` when it has textures (paths written relative to the OBJ's folder).
/// Both files are written atomically. Throws IoError when they cannot be written, InputError when the
/// mesh is invalid.
void write_obj(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace forensim
