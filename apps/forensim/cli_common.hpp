#pragma once
/// Helpers shared by the CLI's subcommands: what kind of data a path holds, and short formatting.

#include <filesystem>
#include <string>

#include "core/types.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/tet_mesh.hpp"
#include "mesh_io/gltf_writer.hpp"

namespace forensim::cli {

/// What a path on the command line holds, judged from its extension (and a folder = DICOM series).
enum class DataKind { surface_mesh, tet_mesh, volume };

/// Classifies a path: .nrrd/.nhdr/.mhd/.mha/.dcm and folders are volumes; .msh/.node/.ele/.vtu are tet
/// meshes; everything else is a surface mesh for Assimp. Throws IoError when the path does not exist.
DataKind classify_path(const std::filesystem::path& path);

/// Reads a tet mesh by extension: .msh (Gmsh), .node/.ele (TetGen), .vtu (VTK).
TetMesh read_tet_mesh(const std::filesystem::path& path);
/// Writes a tet mesh by extension: .msh (Gmsh 4.1 binary), .node or .ele (TetGen), .vtu (VTK, zlib).
void write_tet_mesh(const std::filesystem::path& path, const TetMesh& mesh);

/// "123.4 x 56.7 x 89.0 mm".
std::string format_size_mm(const Vec3& size);
/// Seconds with two decimals, "1.23 s".
std::string format_seconds(double seconds);
/// An integer with thousands separators, "1 234 567".
std::string format_count(std::size_t n);
/// A skull as a glTF node named `name`, in the bone material forensim's scenes use.
GltfMeshNode skull_gltf_node(const std::string& name, const TriMesh& skull);

}  // namespace forensim::cli
