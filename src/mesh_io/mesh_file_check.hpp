#pragma once
/// Cheap structural checks of mesh files before a general-purpose parser (Assimp) reads them. Counts
/// declared in headers (PLY element counts and list lengths, binary STL triangle counts, GLB chunk lengths,
/// glTF accessor sizes) and OBJ face indices are checked against the file's actual size, so a hostile or
/// truncated file cannot make the parser allocate absurd amounts of memory or read out of bounds.

#include <filesystem>
#include <string>

namespace forensim {

/// Checks `path` by its extension (.ply, .stl, .obj, .glb, .gltf; other formats only for emptiness).
/// Throws IoError when it cannot be read, InputError(path, location, problem) naming the first problem.
/// Returns the bytes Assimp must read in place of the file, or an empty string when it reads the file as it is:
/// Assimp 5.2.5 skips one line feed after a PLY's `end_header` line even in a binary file, so a binary body whose
/// first byte is 0x0A (about one real file in 256) comes back with one line feed added after the header, for
/// Assimp::Importer::ReadFileFromMemory.
std::string check_mesh_file(const std::filesystem::path& path);

}  // namespace forensim
