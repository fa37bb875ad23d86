// Fuzzes the NRRD reader (volume/nrrd_reader.hpp) on attached-header files: header fields, raw, gzip and text
// encodings, skips, and data file names (resolved in the input's scratch folder).

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "volume/nrrd_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = forensim::fuzz::write_input(forensim::fuzz::bytes(data, size), "input.nrrd");
  try {
    forensim::fuzz::require_valid(forensim::read_nrrd(path), "read_nrrd");
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
