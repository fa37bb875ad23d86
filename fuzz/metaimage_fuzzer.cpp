// Fuzzes the MetaImage reader (volume/metaimage_reader.hpp) on .mha files: header keys, local raw, text and
// zlib data, and data file names (resolved in the input's scratch folder).

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "volume/metaimage_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = forensim::fuzz::write_input(forensim::fuzz::bytes(data, size), "input.mha");
  try {
    forensim::fuzz::require_valid(forensim::read_metaimage(path), "read_metaimage");
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
