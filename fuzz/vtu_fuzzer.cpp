// Fuzzes the VTK XML UnstructuredGrid readers (tet_io/vtu_reader.hpp): parse_vtu (tetrahedra) and
// parse_vtu_surface (triangles) on the same bytes: XML, ascii/base64/appended arrays, zlib blocks.

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "tet_io/vtu_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = forensim::fuzz::bytes(data, size);
  try {
    forensim::fuzz::require_valid(forensim::parse_vtu(bytes, "fuzz.vtu"), "parse_vtu");
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  try {
    forensim::fuzz::require_valid(forensim::parse_vtu_surface(bytes, "fuzz.vtu"), "parse_vtu_surface");
  } catch (const forensim::Error&) {
  }
  return 0;
}
