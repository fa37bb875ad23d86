#pragma once
/// The built-in skin meshes a wound can be painted on without a file ("forearm-uv", the forearm phantom with
/// its UV atlas, and "cylinder", a UV cylinder), built once on first use and kept, with their GLB encoding
/// for the browser's wound editor. Thread-safe.

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "geometry/tri_mesh.hpp"

namespace forensim {

class BuiltinMeshes {
 public:
  BuiltinMeshes();
  /// Names of the built-in meshes.
  static std::vector<std::string> names();
  /// True when `name` is a built-in mesh.
  static bool known(const std::string& name);
  /// The mesh (mm, with UVs). Throws InputError for an unknown name.
  const TriMesh& mesh(const std::string& name);
  /// The mesh as GLB bytes (metres, as glTF specifies; UV v flipped as glTF specifies).
  const std::string& glb(const std::string& name);

 private:
  // Each mesh is built once, on its own (a request for the cylinder does not wait for the forearm).
  struct Entry {
    std::once_flag mesh_once, glb_once;
    std::unique_ptr<const TriMesh> mesh;
    std::string glb;
  };
  std::map<std::string, std::unique_ptr<Entry>> m_entries;  // fixed at construction: read without a lock
};

}  // namespace forensim
