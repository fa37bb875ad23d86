// Fuzzes JPEG decoding (image/jpeg_io.hpp: decode_jpeg, stb_image behind forensim's size checks) and the
// PNG-or-JPEG sniffing of decode_image that embedded glTF textures go through.

#include <cstddef>
#include <cstdint>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "image/jpeg_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = forensim::fuzz::bytes(data, size);
  try {
    forensim::decode_image(bytes, "fuzz input");
  } catch (const forensim::Error&) {
    // Rejected with forensim's own error: the expected outcome for a broken file.
  }
  return 0;
}
