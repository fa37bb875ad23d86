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
void check_mesh_file(const std::filesystem::path& path);

/// Assimp 5.2.5 skips one line feed after a PLY's `end_header` line even in a binary file, so a binary body
/// whose first byte is 0x0A (about one real file in 256) is read one byte off. For such a file (checked by
/// check_mesh_file first) returns its bytes with one line feed added after the header, for
/// Assimp::Importer::ReadFileFromMemory; returns an empty string for every other file, which reads as it is.
std::string ply_bytes_for_assimp(const std::filesystem::path& path);

}  // namespace forensim
