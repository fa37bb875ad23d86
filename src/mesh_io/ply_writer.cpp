#include "mesh_io/ply_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "mesh_io/uv_seam_split.hpp"

namespace forensim {
namespace {

class PlyBody {
 public:
  explicit PlyBody(bool binary) : m_binary(binary) {}
  void add_float(double value) {
    if (m_binary) {
      const float f = static_cast<float>(value);
      append_raw(&f, 4);
    } else {
      char buffer[32];
      const auto result = std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(value));
      separate();
      m_bytes.append(buffer, result.ptr);
    }
  }
  void add_uchar(unsigned value) {
    if (m_binary) {
      m_bytes.push_back(static_cast<char>(value));
    } else {
      separate();
      m_bytes += std::to_string(value);
    }
  }
  void add_int(Index value) {
    if (m_binary) {
      append_raw(&value, 4);
    } else {
      separate();
      m_bytes += std::to_string(value);
    }
  }
  void end_element() {
    if (!m_binary) {
      m_bytes += '\n';
      m_line_start = true;
    }
  }
  std::string& bytes() { return m_bytes; }

 private:
  void append_raw(const void* p, std::size_t n) {  // little-endian hosts (x86-64, ARM64)
    const auto* c = static_cast<const char*>(p);
    m_bytes.append(c, n);
  }
  void separate() {
    if (!m_line_start) m_bytes += ' ';
    m_line_start = false;
  }
  bool m_binary;
  bool m_line_start = true;
  std::string m_bytes;
};

unsigned to_uchar(float c) {
  return static_cast<unsigned>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

void write_ply(const std::filesystem::path& path, const TriMesh& mesh, const PlyWriteOptions& options) {
  mesh.validate("mesh written to " + path.string());
  const SeamSplitMesh split = split_uv_seams(mesh);
  const bool binary = options.format == PlyFormat::binary_little_endian;

  std::string header = "ply\nformat ";
  header += binary ? "binary_little_endian" : "ascii";
  header += " 1.0\ncomment forensim surface mesh, millimetres\n";
  header += "element vertex " + std::to_string(split.source_vertex.size()) + "\n";
  header += "property float x\nproperty float y\nproperty float z\n";
  if (mesh.has_normals()) header += "property float nx\nproperty float ny\nproperty float nz\n";
  if (mesh.has_colors())
    header += "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n";
  if (mesh.has_uvs()) header += "property float s\nproperty float t\n";
  header += "element face " + std::to_string(split.triangles.size()) + "\n";
  header += "property list uchar int vertex_indices\nend_header\n";

  PlyBody body(binary);
  body.bytes() = std::move(header);
  for (std::size_t i = 0; i < split.source_vertex.size(); ++i) {
    const auto v = static_cast<std::size_t>(split.source_vertex[i]);
    for (int c = 0; c < 3; ++c) body.add_float(mesh.positions[v][c]);
    if (mesh.has_normals()) {
      for (int c = 0; c < 3; ++c) body.add_float(mesh.normals[v][c]);
    }
    if (mesh.has_colors()) {
      for (int c = 0; c < 4; ++c) body.add_uchar(to_uchar(mesh.colors[v][c]));
    }
    if (mesh.has_uvs()) {
      body.add_float(split.uvs[i][0]);
      body.add_float(split.uvs[i][1]);
    }
    body.end_element();
  }
  for (const Tri& t : split.triangles) {
    body.add_uchar(3);
    for (Index i : t) body.add_int(i);
    body.end_element();
  }
  write_file_atomic(path, body.bytes());
}

}  // namespace forensim
