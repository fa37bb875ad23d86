#pragma once
/// JPEG reading through stb_image (Debian's libstb): scanned skin textures, such as head scans' colour maps,
/// usually come as JPEG. Baseline and progressive, grey or colour; hostile files (absurd declared sizes,
/// truncated or corrupt data) are rejected with InputError.

#include <filesystem>
#include <string>
#include <string_view>

#include "image/image.hpp"

namespace forensim {

/// Decodes JPEG bytes into an RGB (or grey) image with colour decoded from sRGB to linear light (tagged
/// linear), or kept as stored and tagged data when `linear_colour` is false (specular and normal maps).
/// `source` names the bytes in errors. Throws InputError for data that is not a valid JPEG or declares more
/// than 2^28 pixels.
Image decode_jpeg(std::string_view bytes, const std::string& source = "JPEG data", bool linear_colour = true);
/// decode_jpeg on a file. Throws IoError when it cannot be read.
Image read_jpeg(const std::filesystem::path& path, bool linear_colour = true);

/// Decodes PNG or JPEG bytes, chosen by their first bytes (an embedded texture of a glTF): colour decoded to
/// linear light. `source` names the bytes in errors. Throws InputError for other data.
Image decode_image(std::string_view bytes, const std::string& source);
/// Reads a PNG, JPEG or OpenEXR file, chosen by its first bytes (not its name): colour PNG and JPEG are
/// decoded to linear light, EXR is linear already. Throws InputError for other formats, naming the file.
Image read_image(const std::filesystem::path& path);

}  // namespace forensim
