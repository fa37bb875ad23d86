// Fuzzes PNG decoding (image/png_io.hpp: decode_png, libpng behind forensim's size and chunk checks) with both
// transfers, sRGB decoding and identity.

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "image/png_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = forensim::fuzz::bytes(data, size);
  // The transfer changes only the per-sample conversion; one bit of the input picks it.
  const auto transfer =
      size > 0 && (data[size - 1] & 1) ? forensim::PngTransfer::identity : forensim::PngTransfer::automatic;
  try {
    forensim::decode_png(bytes, "fuzz input", transfer);
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
