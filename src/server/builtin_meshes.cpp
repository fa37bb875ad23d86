#include "server/builtin_meshes.hpp"

#include <unistd.h>

#include <filesystem>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "phantoms/forearm_uv.hpp"
#include "wound/uv_cylinder.hpp"

namespace forensim {

std::vector<std::string> BuiltinMeshes::names() {
  return {"forearm-uv", "cylinder"};
}

bool BuiltinMeshes::known(const std::string& name) {
  return name == "forearm-uv" || name == "cylinder";
}

BuiltinMeshes::BuiltinMeshes() {
  for (const std::string& name : names()) m_entries[name] = std::make_unique<Entry>();
}

const TriMesh& BuiltinMeshes::mesh(const std::string& name) {
  if (!known(name)) throw InputError("built-in mesh", name, "unknown (known: forearm-uv, cylinder)");
  Entry& e = *m_entries.at(name);
  std::call_once(e.mesh_once, [&] {
    e.mesh = std::make_unique<const TriMesh>(name == "forearm-uv" ? make_forearm_uv().mesh : make_uv_cylinder());
  });
  return *e.mesh;
}

const std::string& BuiltinMeshes::glb(const std::string& name) {
  const TriMesh& m = mesh(name);
  Entry& e = *m_entries.at(name);
  std::call_once(e.glb_once, [&] {
    // The glTF writer writes files; encode through a private temporary file.
    const std::filesystem::path tmp =
        std::filesystem::temp_directory_path() / ("forensim-serve-" + std::to_string(::getpid()) + "-" + name + ".glb");
    write_gltf(tmp, m);
    e.glb = read_file(tmp);
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
  });
  return e.glb;
}

}  // namespace forensim
