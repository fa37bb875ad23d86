// Fuzzes surface mesh import (mesh_io/mesh_import.hpp): the structural checks of mesh_file_check and then
// Assimp, on the input saved as a file whose extension FORENSIM_FUZZ_MESH_EXTENSION picks (".obj", ".ply",
// ".stl", ".gltf", ".glb": one fuzz target per format, built from this file).

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "mesh_io/mesh_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path =
      forensim::fuzz::write_input(forensim::fuzz::bytes(data, size), "input" FORENSIM_FUZZ_MESH_EXTENSION);
  try {
    const forensim::ImportedMesh imported = forensim::import_mesh_with_textures(path);
    forensim::fuzz::require_valid(imported.mesh, "import_mesh");
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
