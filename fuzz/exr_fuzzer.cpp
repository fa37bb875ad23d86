// Fuzzes the OpenEXR reader (image/exr_io.hpp: read_exr, forensim's header checks before OpenEXR reads the
// file) on the input saved as a file.

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "image/exr_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = forensim::fuzz::write_input(forensim::fuzz::bytes(data, size), "input.exr");
  try {
    forensim::read_exr(path);
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
