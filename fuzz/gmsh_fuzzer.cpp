// Fuzzes the Gmsh MSH reader (tet_io/gmsh_io.hpp: parse_gmsh): MSH 4.1 ASCII and binary, MSH 2.2 ASCII,
// entities, physical names and node/element data views.

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "tet_io/gmsh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    forensim::fuzz::require_valid(forensim::parse_gmsh(forensim::fuzz::bytes(data, size), "fuzz.msh"), "parse_gmsh");
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
