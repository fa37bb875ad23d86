#include "mesh_io/mesh_writer.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "core/error.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "mesh_io/obj_writer.hpp"
#include "mesh_io/ply_writer.hpp"
#include "mesh_io/stl_writer.hpp"

namespace forensim {

void write_mesh(const std::filesystem::path& path, const TriMesh& mesh) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".obj") {
    write_obj(path, mesh);
  } else if (ext == ".ply") {
    write_ply(path, mesh);
  } else if (ext == ".stl") {
    write_stl(path, mesh);
  } else if (ext == ".glb" || ext == ".gltf") {
    write_gltf(path, mesh);
  } else {
    throw InputError(path.string(), "", "unknown mesh format '" + ext + "' (use .obj, .ply, .stl, .glb or .gltf)");
  }
}

}  // namespace forensim
