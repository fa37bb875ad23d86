#pragma once
/// PNG reading and writing through libpng. Readers accept 1/2/4/8/16-bit grey, grey+alpha, palette, RGB
/// and RGBA (interlaced or not) and reject hostile files (absurd declared sizes, truncated or corrupt
/// data) with InputError. Writers are atomic.

#include <filesystem>
#include <string>
#include <string_view>

#include "image/image.hpp"

namespace forensim {

/// How PNG sample values map to image values.
enum class PngTransfer {
  automatic,  ///< reading: colour -> linear (sRGB decoded), tagged linear; writing: follow the image's encoding
  srgb,       ///< the PNG holds sRGB-encoded colour: decode to linear on read, encode on write
  identity,   ///< values are copied as they are (display-referred pictures, normal maps, masks)
};

struct PngWriteOptions {
  int bit_depth = 8;                              ///< 8 or 16
  PngTransfer transfer = PngTransfer::automatic;  ///< automatic: sRGB-encode linear images, else copy
  int compression_level = 6;                      ///< zlib level 0..9
};

/// Reads a PNG file into an image of 1 to 4 channels with values in [0,1]. With automatic or srgb
/// transfer colour channels are decoded to linear light (alpha never) and the image is tagged linear;
/// with identity values are kept as stored and the image is tagged data (retag with set_encoding).
/// Throws IoError when the file cannot be read, InputError when it is not a valid, sane PNG.
Image read_png(const std::filesystem::path& path, PngTransfer transfer = PngTransfer::automatic);
/// Same as read_png for PNG bytes held in memory; `source` names them in errors.
Image decode_png(std::string_view bytes, const std::string& source = "PNG data",
                 PngTransfer transfer = PngTransfer::automatic);
/// Writes `image` as PNG (grey, grey+alpha, RGB or RGBA after its channel count) atomically.
/// Values are clamped to [0,1] and rounded. Throws IoError, or InputError for an empty image or bad options.
void write_png(const std::filesystem::path& path, const Image& image, const PngWriteOptions& options = {});
/// PNG file bytes of `image` (for embedding in glTF buffers and HTML data URIs).
std::string encode_png(const Image& image, const PngWriteOptions& options = {});

}  // namespace forensim
