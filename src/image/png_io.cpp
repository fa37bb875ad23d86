#include "image/png_io.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <limits>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "image/color.hpp"

namespace forensim {
namespace {

// libpng reports errors by longjmp. Every function that calls libpng and sets a jump point below holds
// only trivially destructible locals, so the jump skips no destructor; the C++ exception is thrown by the
// caller after the C frame has returned.
struct PngContext {
  const unsigned char* data = nullptr;  // reading: the file bytes
  std::size_t size = 0;
  std::size_t offset = 0;
  std::string* output = nullptr;  // writing: the encoded bytes
  char message[256] = {};
};

void on_error(png_structp png, png_const_charp message) {
  auto* context = static_cast<PngContext*>(png_get_error_ptr(png));
  std::snprintf(context->message, sizeof(context->message), "%s", message ? message : "libpng error");
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

void on_read(png_structp png, png_bytep out, png_size_t count) {
  auto* context = static_cast<PngContext*>(png_get_io_ptr(png));
  if (count > context->size - context->offset) png_error(png, "truncated data (unexpected end of file)");
  std::memcpy(out, context->data + context->offset, count);
  context->offset += count;
}

void on_write(png_structp png, png_bytep in, png_size_t count) {
  auto* context = static_cast<PngContext*>(png_get_io_ptr(png));
  try {
    context->output->append(reinterpret_cast<const char*>(in), count);
  } catch (...) {
    png_error(png, "out of memory while encoding");
  }
}

void on_flush(png_structp) {}

struct Header {
  png_uint_32 width = 0, height = 0;
  int channels = 0, bit_depth = 0;
  std::size_t row_bytes = 0;
};

// Reads the header and sets up the transforms to 8- or 16-bit grey/GA/RGB/RGBA. Returns false on error.
bool read_header(png_structp png, png_infop info, Header* header) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_user_limits(png, 1u << 20, 1u << 20);
  png_set_chunk_malloc_max(png, 16u << 20);
  png_read_info(png, info);
  const int colour_type = png_get_color_type(png, info);
  const int depth = png_get_bit_depth(png, info);
  if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (depth == 16) png_set_swap(png);  // native little-endian uint16 rows
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  header->width = png_get_image_width(png, info);
  header->height = png_get_image_height(png, info);
  header->channels = png_get_channels(png, info);
  header->bit_depth = png_get_bit_depth(png, info);
  header->row_bytes = png_get_rowbytes(png, info);
  return true;
}

bool read_rows(png_structp png, png_infop info, png_bytep* rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, info);
  return true;
}

bool write_all(png_structp png, png_infop info, png_bytep* rows, png_uint_32 width, png_uint_32 height, int depth,
               int colour_type, bool srgb_chunk, int level) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_compression_level(png, level);
  png_set_IHDR(png, info, width, height, depth, colour_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (srgb_chunk) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  if (depth == 16) png_set_swap(png);
  png_write_image(png, rows);
  png_write_end(png, info);
  return true;
}

struct ReadGuard {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~ReadGuard() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

struct WriteGuard {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~WriteGuard() { png_destroy_write_struct(&png, info ? &info : nullptr); }
};

}  // namespace

Image decode_png(std::string_view bytes, const std::string& source, PngTransfer transfer) {
  require_input(bytes.size() >= 8 && png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) == 0, source,
                "byte 0", "not a PNG file (bad signature)");
  PngContext context;
  context.data = reinterpret_cast<const unsigned char*>(bytes.data());
  context.size = bytes.size();
  ReadGuard guard;
  guard.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &context, &on_error, &on_warning);
  if (!guard.png) throw Error("libpng: cannot create read struct");
  guard.info = png_create_info_struct(guard.png);
  if (!guard.info) throw Error("libpng: cannot create info struct");
  png_set_read_fn(guard.png, &context, &on_read);

  Header header;
  if (!read_header(guard.png, guard.info, &header)) throw InputError(source, "header", context.message);
  const std::size_t pixels = static_cast<std::size_t>(header.width) * header.height;
  require_input(header.width > 0 && header.height > 0, source, "header", "empty image");
  require_input(pixels <= max_image_pixels, source, "header",
                "declared size " + std::to_string(header.width) + " x " + std::to_string(header.height) +
                    " exceeds the limit of 2^28 pixels");
  require_input(header.channels >= 1 && header.channels <= 4 && (header.bit_depth == 8 || header.bit_depth == 16),
                source, "header", "unsupported pixel layout");
  const std::size_t expected_row = static_cast<std::size_t>(header.width) * header.channels * (header.bit_depth / 8);
  require_input(header.row_bytes == expected_row, source, "header", "inconsistent row size");
  // Deflate expands at most ~1032:1, so a picture cannot decode to far more bytes than its file holds
  // (checked before allocating for the declared size).
  const std::size_t decoded = header.row_bytes * header.height;
  require_input(decoded / 1100 <= bytes.size() + 1024, source, "header",
                "declared size " + std::to_string(header.width) + " x " + std::to_string(header.height) +
                    " is impossible for a file of " + std::to_string(bytes.size()) + " bytes");

  std::vector<unsigned char> buffer(decoded);
  std::vector<png_bytep> rows(header.height);
  for (png_uint_32 y = 0; y < header.height; ++y) rows[y] = buffer.data() + y * header.row_bytes;
  if (!read_rows(guard.png, guard.info, rows.data())) throw InputError(source, "image data", context.message);

  const bool decode = transfer != PngTransfer::identity;
  Image image(static_cast<int>(header.width), static_cast<int>(header.height), header.channels, 0.0f,
              decode ? PixelEncoding::linear : PixelEncoding::data);
  const int colour_channels = (header.channels == 2 || header.channels == 4) ? header.channels - 1 : header.channels;
  // Lookup tables so decoding costs no pow() per sample.
  std::vector<float> table(header.bit_depth == 16 ? 65536 : 256);
  const float max_value = header.bit_depth == 16 ? 65535.0f : 255.0f;
  std::vector<float> decode_table(table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    table[i] = static_cast<float>(i) / max_value;
    decode_table[i] = decode ? srgb_to_linear(table[i]) : table[i];
  }
  std::vector<float>& out = image.data();
  std::size_t k = 0;
  for (png_uint_32 y = 0; y < header.height; ++y) {
    const unsigned char* row = rows[y];
    for (png_uint_32 x = 0; x < header.width; ++x) {
      for (int c = 0; c < header.channels; ++c, ++k) {
        std::size_t v;
        if (header.bit_depth == 16) {
          std::uint16_t s;
          std::memcpy(&s, row + (static_cast<std::size_t>(x) * header.channels + c) * 2, 2);
          v = s;
        } else {
          v = row[static_cast<std::size_t>(x) * header.channels + c];
        }
        out[k] = c < colour_channels ? decode_table[v] : table[v];
      }
    }
  }
  return image;
}

Image read_png(const std::filesystem::path& path, PngTransfer transfer) {
  const std::string bytes = read_file(path, std::size_t{1} << 30);
  return decode_png(bytes, path.string(), transfer);
}

std::string encode_png(const Image& image, const PngWriteOptions& options) {
  require_input(!image.empty(), "image", "", "cannot write an empty image as PNG");
  require_input(options.bit_depth == 8 || options.bit_depth == 16, "PNG options", "bit_depth",
                "must be 8 or 16, got " + std::to_string(options.bit_depth));
  const bool encode = options.transfer == PngTransfer::srgb ||
                      (options.transfer == PngTransfer::automatic && image.encoding() == PixelEncoding::linear);
  const int channels = image.channels();
  const int colour_channels = (channels == 2 || channels == 4) ? channels - 1 : channels;
  const int bytes_per_sample = options.bit_depth / 8;
  const std::size_t row_bytes = static_cast<std::size_t>(image.width()) * channels * bytes_per_sample;
  std::vector<unsigned char> buffer(row_bytes * image.height());
  const float max_value = options.bit_depth == 16 ? 65535.0f : 255.0f;
  const std::vector<float>& in = image.data();
  for (std::size_t i = 0; i < in.size(); ++i) {
    const int c = static_cast<int>(i % static_cast<std::size_t>(channels));
    float v = in[i];
    if (encode && c < colour_channels) v = linear_to_srgb(v);
    v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
    const auto q = static_cast<std::uint16_t>(std::lround(v * max_value));
    if (bytes_per_sample == 2) {
      std::memcpy(buffer.data() + i * 2, &q, 2);
    } else {
      buffer[i] = static_cast<unsigned char>(q);
    }
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height()));
  for (int y = 0; y < image.height(); ++y) rows[static_cast<std::size_t>(y)] = buffer.data() + y * row_bytes;

  std::string output;
  output.reserve(buffer.size() / 2 + 1024);
  PngContext context;
  context.output = &output;
  WriteGuard guard;
  guard.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &context, &on_error, &on_warning);
  if (!guard.png) throw Error("libpng: cannot create write struct");
  guard.info = png_create_info_struct(guard.png);
  if (!guard.info) throw Error("libpng: cannot create info struct");
  png_set_write_fn(guard.png, &context, &on_write, &on_flush);
  static constexpr int colour_types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                         PNG_COLOR_TYPE_RGB_ALPHA};
  const bool srgb_chunk = encode || image.encoding() == PixelEncoding::srgb;
  if (!write_all(guard.png, guard.info, rows.data(), static_cast<png_uint_32>(image.width()),
                 static_cast<png_uint_32>(image.height()), options.bit_depth, colour_types[channels - 1], srgb_chunk,
                 std::clamp(options.compression_level, 0, 9)))
    throw Error(std::string("libpng: cannot encode PNG: ") + context.message);
  return output;
}

void write_png(const std::filesystem::path& path, const Image& image, const PngWriteOptions& options) {
  write_file_atomic(path, encode_png(image, options));
}

}  // namespace forensim
