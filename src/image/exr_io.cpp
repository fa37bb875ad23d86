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
#include <system_error>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace forensim {
namespace {

std::int32_t read_int32(const std::string& bytes, std::size_t at) {
  const auto b = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + k])); };
  return static_cast<std::int32_t>(b(0) | (b(1) << 8) | (b(2) << 16) | (b(3) << 24));
}

// Walks the first header's attribute list (name, type, size, value) up to its end and checks the
// dataWindow before OpenEXR sizes any table from it, so a tiny hostile file cannot make it allocate
// gigabytes. `head` is the start of the file.
void check_exr_header(const std::string& head, std::uintmax_t file_size, const std::string& source) {
  require_input(head.size() >= 8 && read_int32(head, 0) == 20000630, source, "byte 0",
                "not an OpenEXR file (bad magic number)");
  std::size_t at = 8;
  const auto read_string = [&](const char* what) {
    const std::size_t end = head.find('\0', at);
    require_input(end != std::string::npos && end - at < 256, source, "byte " + std::to_string(at),
                  std::string("unterminated or overlong attribute ") + what);
    std::string text = head.substr(at, end - at);
    at = end + 1;
    return text;
  };
  for (int attributes = 0; attributes < 10000; ++attributes) {
    const std::string name = read_string("name");
    require_input(!name.empty(), source, "header", "no dataWindow attribute");
    const std::string type = read_string("type");
    require_input(at + 4 <= head.size(), source, "byte " + std::to_string(at), "truncated header");
    const std::int32_t size = read_int32(head, at);
    at += 4;
    require_input(size >= 0 && static_cast<std::size_t>(size) <= head.size() - at, source, "byte " + std::to_string(at),
                  "attribute '" + name + "' larger than the header");
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
      require_input(static_cast<unsigned long long>(w) * static_cast<unsigned long long>(h) / 4096 <= file_size + 1024,
                    source, "dataWindow",
                    "data window " + std::to_string(w) + " x " + std::to_string(h) + " is impossible for a file of " +
                        std::to_string(file_size) + " bytes");
      return;
    }
    at += static_cast<std::size_t>(size);
  }
  throw InputError(source, "header", "too many attributes");
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
    // OpenEXR addresses the slice with data-window coordinates: offset the base pointer accordingly.
    for (int c = 0; c < channels; ++c) {
      char* base = reinterpret_cast<char*>(image.data().data() + c) -
                   static_cast<std::ptrdiff_t>(window.min.x) * static_cast<std::ptrdiff_t>(x_stride) -
                   static_cast<std::ptrdiff_t>(window.min.y) * static_cast<std::ptrdiff_t>(y_stride);
      frame.insert(names[static_cast<std::size_t>(c)],
                   Imf::Slice(Imf::FLOAT, base, x_stride, y_stride, 1, 1,
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
