#include "image/jpeg_io.hpp"

#include <stb/stb_image.h>

#include <cstdint>
#include <memory>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "image/color.hpp"
#include "image/exr_io.hpp"
#include "image/png_io.hpp"

namespace forensim {

Image decode_jpeg(std::string_view bytes, const std::string& source, bool linear_colour) {
  if (bytes.size() < 4 || static_cast<unsigned char>(bytes[0]) != 0xFF ||
      static_cast<unsigned char>(bytes[1]) != 0xD8) {
    throw InputError(source, "byte 0", "is not a JPEG file (no SOI marker)");
  }
  if (bytes.size() > static_cast<std::size_t>(INT32_MAX)) throw InputError(source, "", "JPEG data larger than 2 GiB");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int length = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, length, &width, &height, &channels))
    throw InputError(source, "header", std::string("is not a readable JPEG: ") + stbi_failure_reason());
  if (width <= 0 || height <= 0 || static_cast<std::int64_t>(width) * height > (std::int64_t{1} << 28))
    throw InputError(source, "header",
                     "declares " + std::to_string(width) + " x " + std::to_string(height) + " pixels (limit 2^28)");
  // Every 8 x 8 block costs at least one bit of entropy-coded data per component, so no JPEG holds more than 512
  // pixels per byte; stb decodes a cut-off file as if it were whole, so a few bytes declaring 150 million
  // pixels would otherwise become a 1.8 GB image (found by fuzz/jpeg). The bound is 8 times that.
  const auto pixels_declared = static_cast<std::int64_t>(width) * height;
  if (pixels_declared > static_cast<std::int64_t>(bytes.size()) * 4096)
    throw InputError(source, "header",
                     "declares " + std::to_string(width) + " x " + std::to_string(height) +
                         " pixels, more than a JPEG of " + std::to_string(bytes.size()) + " bytes can hold");
  const int wanted = channels <= 2 ? 1 : 3;
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(data, length, &width, &height, &channels, wanted), stbi_image_free);
  if (!pixels) throw InputError(source, "data", std::string("cannot be decoded: ") + stbi_failure_reason());
  Image image(width, height, wanted, 0.0f, linear_colour ? PixelEncoding::linear : PixelEncoding::data);
  const stbi_uc* p = pixels.get();
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < wanted; ++c) {
        const float v = static_cast<float>(*p++) / 255.0f;
        image.at(x, y, c) = linear_colour ? srgb_to_linear(v) : v;
      }
    }
  }
  return image;
}

Image read_jpeg(const std::filesystem::path& path, bool linear_colour) {
  return decode_jpeg(read_file(path), path.string(), linear_colour);
}

namespace {

unsigned byte_at(std::string_view bytes, std::size_t i) {
  return i < bytes.size() ? static_cast<unsigned char>(bytes[i]) : 0u;
}

bool is_png(std::string_view b) {
  return byte_at(b, 0) == 0x89 && byte_at(b, 1) == 'P' && byte_at(b, 2) == 'N' && byte_at(b, 3) == 'G';
}

bool is_jpeg(std::string_view b) {
  return byte_at(b, 0) == 0xFF && byte_at(b, 1) == 0xD8;
}

}  // namespace

Image decode_image(std::string_view bytes, const std::string& source) {
  if (is_png(bytes)) return decode_png(bytes, source);
  if (is_jpeg(bytes)) return decode_jpeg(bytes, source);
  throw InputError(source, "byte 0", "is not a PNG or JPEG image");
}

Image read_image(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  if (is_png(bytes) || is_jpeg(bytes)) return decode_image(bytes, path.string());
  if (byte_at(bytes, 0) == 0x76 && byte_at(bytes, 1) == 0x2F && byte_at(bytes, 2) == 0x31 && byte_at(bytes, 3) == 0x01)
    return read_exr(path);
  throw InputError(path.string(), "byte 0", "is not a PNG, JPEG or OpenEXR image");
}

}  // namespace forensim
