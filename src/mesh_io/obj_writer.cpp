#include "mesh_io/obj_writer.hpp"

#include <charconv>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace forensim {
namespace {

/// Appends `value` in the shortest form that reads back exactly.
void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

/// Texture path as the .mtl should name it: relative to the OBJ's folder when possible.
std::string mtl_texture_path(const std::string& texture, const std::filesystem::path& folder) {
  const std::filesystem::path p(texture);
  if (p.is_relative() || folder.empty()) return p.generic_string();
  const std::filesystem::path relative = p.lexically_proximate(folder);
  return relative.generic_string();
}

}  // namespace

void write_obj(const std::filesystem::path& path, const TriMesh& mesh) {
  mesh.validate("mesh written to " + path.string());
  std::filesystem::path mtl_path = path;
  mtl_path.replace_extension(".mtl");
  const std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
  const Material& m = mesh.material;

  std::string mtl = "# forensim material\nnewmtl ";
  mtl += m.name.empty() ? "material" : m.name;
  mtl += "\nKd ";
  for (int c = 0; c < 3; ++c) {
    append_number(mtl, m.base_color[c]);
    mtl += c < 2 ? " " : "\n";
  }
  mtl += "d ";
  append_number(mtl, m.base_color[3]);
  mtl += "\nPr ";
  append_number(mtl, m.roughness);
  mtl += "\nPm ";
  append_number(mtl, m.metallic);
  mtl += "\n";
  if (!m.base_color_texture.empty()) mtl += "map_Kd " + mtl_texture_path(m.base_color_texture, folder) + "\n";
  if (!m.normal_texture.empty()) mtl += "norm " + mtl_texture_path(m.normal_texture, folder) + "\n";
  if (!m.roughness_texture.empty()) mtl += "map_Pr " + mtl_texture_path(m.roughness_texture, folder) + "\n";

  std::string obj = "# forensim surface mesh (millimetres)\nmtllib " + mtl_path.filename().string() + "\n";
  obj.reserve(obj.size() + mesh.positions.size() * 60 + mesh.triangles.size() * 40);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    obj += "v";
    for (int c = 0; c < 3; ++c) {
      obj += ' ';
      append_number(obj, mesh.positions[v][c]);
    }
    if (mesh.has_colors()) {
      for (int c = 0; c < 3; ++c) {
        obj += ' ';
        append_number(obj, mesh.colors[v][c]);
      }
    }
    obj += '\n';
  }
  for (const Vec3& n : mesh.normals) {
    obj += "vn";
    for (int c = 0; c < 3; ++c) {
      obj += ' ';
      append_number(obj, n[c]);
    }
    obj += '\n';
  }
  for (const Vec2& uv : mesh.uvs) {
    obj += "vt ";
    append_number(obj, uv[0]);
    obj += ' ';
    append_number(obj, uv[1]);
    obj += '\n';
  }
  obj += "usemtl ";
  obj += m.name.empty() ? "material" : m.name;
  obj += '\n';
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    obj += 'f';
    for (int c = 0; c < 3; ++c) {
      const std::string v = std::to_string(mesh.triangles[f][c] + 1);
      obj += ' ';
      obj += v;
      if (mesh.has_uvs()) {
        obj += '/';
        obj += std::to_string(mesh.triangle_uvs[f][c] + 1);
      }
      if (mesh.has_normals()) {
        obj += mesh.has_uvs() ? "/" : "//";
        obj += v;
      }
    }
    obj += '\n';
  }
  write_file_atomic(mtl_path, mtl);
  write_file_atomic(path, obj);
}

}  // namespace forensim
