#pragma once
/// Cheap structural checks of mesh files before a general-purpose parser (Assimp) reads them. Counts
/// declared in headers (PLY element counts and list lengths, binary STL triangle counts, GLB chunk lengths,
/// glTF accessor sizes) and OBJ face indices are checked against the file's actual size, so a hostile or
/// truncated file cannot make the parser allocate absurd amounts of memory or read out of bounds.

#include <filesystem>

namespace forensim {

/// Checks `path` by its extension (.ply, .stl, .obj, .glb, .gltf; other formats only for emptiness).
/// Throws IoError when it cannot be read, InputError(path, location, problem) naming the first problem.
void check_mesh_file(const std::filesystem::path& path);

}  // namespace forensim
