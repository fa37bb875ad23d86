#include "image/exr_io.hpp"

#include <Imath/ImathBox.h>
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace forensim {
namespace {

std::int32_t read_int32(const std::string& bytes, std::size_t at) {
  const auto b = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + k])); };
  return static_cast<std::int32_t>(b(0) | (b(1) << 8) | (b(2) << 16) | (b(3) << 24));
}

// Bytes of the attribute types that OpenEXR reads with a fixed layout whatever size the file declares (so a
// wrong size would leave its reading out of step with the sizes walked here), or -1.
int fixed_attribute_size(const std::string& type) {
  static const std::pair<const char*, int> sizes[] = {{"box2i", 16},
                                                      {"box2f", 16},
                                                      {"chromaticities", 32},
                                                      {"compression", 1},
                                                      {"deepImageState", 1},
                                                      {"double", 8},
                                                      {"envmap", 1},
                                                      {"float", 4},
                                                      {"int", 4},
                                                      {"keycode", 28},
                                                      {"lineOrder", 1},
                                                      {"m33f", 36},
                                                      {"m33d", 72},
                                                      {"m44f", 64},
                                                      {"m44d", 128},
                                                      {"rational", 8},
                                                      {"tiledesc", 9},
                                                      {"timecode", 8},
                                                      {"v2i", 8},
                                                      {"v2f", 8},
                                                      {"v2d", 16},
                                                      {"v3i", 12},
                                                      {"v3f", 12},
                                                      {"v3d", 24}};
  for (const auto& [name, size] : sizes) {
    if (type == name) return size;
  }
  return -1;
}

// Checks that an attribute's value is laid out as OpenEXR will read it: fixed-size types have their size, a
// channel list's entries (name, 16 bytes) end exactly with the attribute, and every string of a string vector
// fits in it (OpenEXR allocates each from its declared length). `value` is the attribute's bytes.
void check_exr_attribute(const std::string& name, const std::string& type, std::string_view value,
                         const std::string& source) {
  const std::string where = "attribute '" + name + "'";
  const int fixed = fixed_attribute_size(type);
  if (fixed >= 0) {
    require_input(value.size() == static_cast<std::size_t>(fixed), source, where,
                  "a " + type + " takes " + std::to_string(fixed) + " bytes, not " + std::to_string(value.size()));
  } else if (type == "chlist") {
    std::size_t at = 0;
    while (true) {
      const std::size_t end = value.find('\0', at);
      require_input(end != std::string_view::npos && end - at < 256, source, where, "unterminated channel name");
      if (end == at) {
        require_input(end + 1 == value.size(), source, where, "bytes after the channel list's end");
        break;
      }
      at = end + 1 + 16;  // pixel type, linear flag, 3 reserved bytes, x and y sampling
      require_input(at <= value.size(), source, where, "truncated channel");
    }
  } else if (type == "stringvector") {
    std::size_t at = 0;
    while (at < value.size()) {
      require_input(value.size() - at >= 4, source, where, "truncated string length");
      const std::int32_t length = read_int32(std::string(value.substr(at, 4)), 0);
      at += 4;
      require_input(length >= 0 && static_cast<std::size_t>(length) <= value.size() - at, source, where,
                    "string of " + std::to_string(length) + " bytes in " + std::to_string(value.size() - at));
      at += static_cast<std::size_t>(length);
    }
  }
}

// Walks every header's attribute list (name, type, size, value) to its end, all parts of a multi-part file,
// before OpenEXR reads any: each attribute must fit in the header bytes and be laid out as OpenEXR reads it,
// and each dataWindow must be sane, so a tiny hostile file cannot make OpenEXR allocate gigabytes (an attribute
// after the dataWindow, or one behind a channel list longer than its declared size, once could: found by
// fuzz/exr). `head` is the start of the file.
void check_exr_header(const std::string& head, std::uintmax_t file_size, const std::string& source) {
  require_input(head.size() >= 8 && read_int32(head, 0) == 20000630, source, "byte 0",
                "not an OpenEXR file (bad magic number)");
  const bool multi_part = (read_int32(head, 4) & 0x1000) != 0;
  std::size_t at = 8;
  const auto read_string = [&](const char* what) {
    const std::size_t end = head.find('\0', at);
    require_input(end != std::string::npos && end - at < 256, source, "byte " + std::to_string(at),
                  std::string("unterminated or overlong attribute ") + what);
    std::string text = head.substr(at, end - at);
    at = end + 1;
    return text;
  };
  for (int part = 0; part < 10000; ++part) {
    bool data_window = false;
    std::uint64_t window_pixels = 0, tile_pixels = 0;
    for (int attributes = 0;; ++attributes) {
      require_input(attributes < 10000, source, "header", "too many attributes");
      const std::string name = read_string("name");
      if (name.empty()) break;  // the header's end
      const std::string type = read_string("type");
      require_input(at + 4 <= head.size(), source, "byte " + std::to_string(at), "truncated header");
      const std::int32_t size = read_int32(head, at);
      at += 4;
      require_input(size >= 0 && static_cast<std::size_t>(size) <= head.size() - at, source,
                    "byte " + std::to_string(at), "attribute '" + name + "' larger than the header");
      check_exr_attribute(name, type, std::string_view(head).substr(at, static_cast<std::size_t>(size)), source);
      if (name == "dataWindow") {
        require_input(type == "box2i" && size == 16, source, "dataWindow", "must be a box2i");
        const long long x0 = read_int32(head, at), y0 = read_int32(head, at + 4);
        const long long x1 = read_int32(head, at + 8), y1 = read_int32(head, at + 12);
        const long long w = x1 - x0 + 1, h = y1 - y0 + 1;
        require_input(w > 0 && h > 0, source, "dataWindow", "empty data window");
        require_input(
            static_cast<unsigned long long>(w) * static_cast<unsigned long long>(h) <= max_image_pixels, source,
            "dataWindow",
            "data window " + std::to_string(w) + " x " + std::to_string(h) + " exceeds the limit of 2^28 pixels");
        // Compressed EXR rarely beats ~1000:1 on a half channel; far larger claims are hostile.
        require_input(
            static_cast<unsigned long long>(w) * static_cast<unsigned long long>(h) / 4096 <= file_size + 1024, source,
            "dataWindow",
            "data window " + std::to_string(w) + " x " + std::to_string(h) + " is impossible for a file of " +
                std::to_string(file_size) + " bytes");
        data_window = true;
        window_pixels = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
      } else if (name == "tiles" && type == "tiledesc") {
        tile_pixels = std::uint64_t{static_cast<std::uint32_t>(read_int32(head, at))} *
                      static_cast<std::uint32_t>(read_int32(head, at + 4));
      }
      at += static_cast<std::size_t>(size);
    }
    require_input(data_window, source, "header", "no dataWindow attribute");
    // OpenEXR allocates a buffer per tile from the tile size alone, which can be far larger than the image (2^27
    // by 2 pixels in a 400-byte file: found by fuzz/exr). A tile may exceed a small image, but not 256 x 256 too.
    require_input(
        tile_pixels <= std::max<std::uint64_t>(window_pixels, 65536), source, "tiles",
        "tiles of " + std::to_string(tile_pixels) + " pixels for an image of " + std::to_string(window_pixels));
    // A multi-part file's headers end with an empty one.
    if (!multi_part) return;
    require_input(at < head.size(), source, "byte " + std::to_string(at), "truncated header list");
    if (head[at] == '\0') return;
  }
  throw InputError(source, "header", "too many parts");
}

}  // namespace

Image read_exr(const std::filesystem::path& path) {
  std::error_code ec;
  const auto file_size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(path.string(), "cannot read: " + ec.message());
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path.string(), "cannot open");
    std::string head(static_cast<std::size_t>(std::min<std::uintmax_t>(file_size, std::uintmax_t{1} << 22)), '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    if (!in) throw IoError(path.string(), "cannot read the header");
    check_exr_header(head, file_size, path.string());
  }
  try {
    Imf::InputFile file(path.string().c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const long long w = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long h = static_cast<long long>(window.max.y) - window.min.y + 1;
    require_input(w > 0 && h > 0, path.string(), "header", "empty data window");
    require_input(static_cast<unsigned long long>(w) * static_cast<unsigned long long>(h) <= max_image_pixels,
                  path.string(), "header",
                  "data window " + std::to_string(w) + " x " + std::to_string(h) + " exceeds the limit of 2^28 pixels");
    // Compressed EXR rarely beats ~1000:1 on a half channel; far larger claims are hostile.
    require_input(static_cast<unsigned long long>(w) * static_cast<unsigned long long>(h) / 4096 <= file_size + 1024,
                  path.string(), "header",
                  "data window " + std::to_string(w) + " x " + std::to_string(h) + " is impossible for a file of " +
                      std::to_string(file_size) + " bytes");
    const Imf::ChannelList& list = file.header().channels();
    std::vector<std::string> names;
    if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B")) {
      names = {"R", "G", "B"};
      if (list.findChannel("A")) names.push_back("A");
    } else if (list.findChannel("Y")) {
      names = {"Y"};
      if (list.findChannel("A")) names.push_back("A");
    } else {
      int count = 0;
      for (auto it = list.begin(); it != list.end(); ++it) {
        if (count++ == 0) names = {it.name()};
      }
      require_input(count == 1, path.string(), "channels",
                    count == 0 ? "no channels" : "no R,G,B or Y channels and more than one channel");
    }
    const int channels = static_cast<int>(names.size());
    Image image(static_cast<int>(w), static_cast<int>(h), channels, 0.0f,
                (channels == 1 && names[0] != "Y") ? PixelEncoding::data : PixelEncoding::linear);
    Imf::FrameBuffer frame;
    const std::size_t x_stride = sizeof(float) * static_cast<std::size_t>(channels);
    const std::size_t y_stride = x_stride * static_cast<std::size_t>(w);
    // OpenEXR addresses the slice with data-window coordinates. Slice::Make offsets the base pointer in integer
    // arithmetic: done on the pointer, a window far from the origin overflowed it (undefined behaviour; found
    // by fuzz/exr).
    for (int c = 0; c < channels; ++c) {
      frame.insert(names[static_cast<std::size_t>(c)],
                   Imf::Slice::Make(Imf::FLOAT, image.data().data() + c, window, x_stride, y_stride, 1, 1,
                                    names[static_cast<std::size_t>(c)] == "A" ? 1.0 : 0.0));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path.string(), "", std::string("not a valid OpenEXR file: ") + e.what());
  }
}

void write_exr(const std::filesystem::path& path, const Image& image, ExrPixelType type) {
  require_input(!image.empty(), "image", "", "cannot write an empty image as EXR");
  static const char* const layouts[4][4] = {{"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
  const int channels = image.channels();
  const Imf::PixelType pixel_type = type == ExrPixelType::half_float ? Imf::HALF : Imf::FLOAT;
  AtomicFile out(path);
  out.release_stream();
  try {
    Imf::Header header(image.width(), image.height());
    header.compression() = Imf::ZIP_COMPRESSION;
    for (int c = 0; c < channels; ++c) header.channels().insert(layouts[channels - 1][c], Imf::Channel(pixel_type));
    Imf::OutputFile file(out.temporary_path().string().c_str(), header);
    Imf::FrameBuffer frame;
    // OpenEXR does not convert pixel types on output: give half channels a half buffer.
    std::vector<half> halves;
    if (pixel_type == Imf::HALF) halves.assign(image.data().begin(), image.data().end());
    const std::size_t sample_size = pixel_type == Imf::HALF ? sizeof(half) : sizeof(float);
    const std::size_t x_stride = sample_size * static_cast<std::size_t>(channels);
    const std::size_t y_stride = x_stride * static_cast<std::size_t>(image.width());
    for (int c = 0; c < channels; ++c) {
      // OpenEXR only reads through this pointer when writing.
      char* base = pixel_type == Imf::HALF ? reinterpret_cast<char*>(halves.data() + c)
                                           : const_cast<char*>(reinterpret_cast<const char*>(image.data().data() + c));
      frame.insert(layouts[channels - 1][c], Imf::Slice(pixel_type, base, x_stride, y_stride));
    }
    file.setFrameBuffer(frame);
    file.writePixels(image.height());
  } catch (const std::exception& e) {
    throw IoError(path.string(), std::string("cannot write EXR: ") + e.what());
  }
  out.commit();
}

}  // namespace forensim
