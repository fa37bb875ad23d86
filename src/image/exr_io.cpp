#include "image/exr_io.hpp"

#include <Imath/ImathBox.h>
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <exception>
#include <string>
#include <system_error>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace forensim {

Image read_exr(const std::filesystem::path& path) {
  std::error_code ec;
  const auto file_size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(path.string(), "cannot read: " + ec.message());
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
