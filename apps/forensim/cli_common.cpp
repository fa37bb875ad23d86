#include "cli_common.hpp"

#include <algorithm>
#include <cstdio>
#include <system_error>

#include "core/error.hpp"
#include "tet_io/gmsh_io.hpp"
#include "tet_io/tetgen_io.hpp"
#include "tet_io/vtu_reader.hpp"
#include "tet_io/vtu_writer.hpp"

namespace forensim::cli {

namespace {
std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}
}  // namespace

DataKind classify_path(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path.string(), "no such file or folder");
  if (std::filesystem::is_directory(path, ec)) return DataKind::volume;
  const std::string ext = lower_extension(path);
  if (ext == ".nrrd" || ext == ".nhdr" || ext == ".mhd" || ext == ".mha" || ext == ".dcm") return DataKind::volume;
  if (ext == ".msh" || ext == ".node" || ext == ".ele" || ext == ".vtu") return DataKind::tet_mesh;
  return DataKind::surface_mesh;
}

TetMesh read_tet_mesh(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".msh") return read_gmsh(path);
  if (ext == ".node" || ext == ".ele") return read_tetgen(path);
  if (ext == ".vtu") return read_vtu(path);
  throw InputError(path.string(), "", "not a tetrahedral mesh format (use .msh, .node/.ele or .vtu)");
}

void write_tet_mesh(const std::filesystem::path& path, const TetMesh& mesh) {
  const std::string ext = lower_extension(path);
  if (ext == ".msh") return write_gmsh(path, mesh, true);
  if (ext == ".node" || ext == ".ele") return write_tetgen(std::filesystem::path(path).replace_extension(), mesh);
  if (ext == ".vtu") return write_vtu(path, mesh);
  throw InputError(path.string(), "", "cannot write a tetrahedral mesh in this format (use .msh, .node or .vtu)");
}

std::string format_size_mm(const Vec3& size) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.1f x %.1f x %.1f mm", size.x(), size.y(), size.z());
  return buf;
}

std::string format_seconds(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, seconds < 10 ? "%.2f s" : "%.1f s", seconds);
  return buf;
}

std::string format_count(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ' ';
    out += digits[i];
  }
  return out;
}

GltfMeshNode skull_gltf_node(const std::string& name, const TriMesh& skull) {
  GltfMeshNode node;
  node.name = name;
  node.mesh = skull;
  node.mesh.material.name = "bone";
  node.mesh.material.base_color = Vec4f(0.85f, 0.8f, 0.7f, 1.0f);
  return node;
}

}  // namespace forensim::cli
