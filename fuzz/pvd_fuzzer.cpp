// Fuzzes the ParaView .pvd collection reader (tet_io/pvd_writer.hpp: parse_pvd) and its XML parser.

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "tet_io/pvd_writer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    forensim::parse_pvd(forensim::fuzz::bytes(data, size), "fuzz.pvd");
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
