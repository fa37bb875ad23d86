#pragma once
/// Stanford PLY export: compact binary meshes for MeshLab, CloudCompare and scanner pipelines.

#include <filesystem>

#include "geometry/tri_mesh.hpp"

namespace forensim {

enum class PlyFormat { binary_little_endian, ascii };

struct PlyWriteOptions {
  PlyFormat format = PlyFormat::binary_little_endian;
};

/// Writes `mesh` as PLY: float x y z, float nx ny nz when it has normals, uchar red green blue alpha when it
/// has colours, float s t when it has UVs, and `list uchar int vertex_indices` faces. PLY's texture
/// coordinates are per vertex, so vertices are split at UV seams (importers that weld by position, such as
/// import_mesh, merge them back). Written atomically. Throws IoError / InputError.
void write_ply(const std::filesystem::path& path, const TriMesh& mesh, const PlyWriteOptions& options = {});

}  // namespace forensim
