#pragma once
/// OpenEXR reading and writing (scene-linear renders, height and moisture maps): RGBA, RGB, grey+alpha
/// and single-channel images stored as half or 32-bit float. Writes are atomic.

#include <filesystem>

#include "image/image.hpp"

namespace forensim {

/// Sample type of the channels in a written EXR file.
enum class ExrPixelType {
  half_float,  ///< 16-bit half: enough for colour, 3 significant digits
  full_float,  ///< 32-bit float: for data (heights, moisture) that needs full precision
};

/// Reads an EXR file. Channels R,G,B[,A] give an RGB(A) image; a single channel (Y or any other name)
/// gives a 1-channel image, Y with A a 2-channel one. The image is tagged linear (data for 1 channel
/// not named Y). Throws IoError when unreadable, InputError when malformed or absurdly large.
Image read_exr(const std::filesystem::path& path);
/// Writes `image` as a scan-line EXR with ZIP compression: 1 channel as Y, 2 as Y,A, 3 as R,G,B, 4 as
/// R,G,B,A. Throws IoError on failure, InputError for an empty image.
void write_exr(const std::filesystem::path& path, const Image& image, ExrPixelType type = ExrPixelType::half_float);

}  // namespace forensim
