#include "volume/image_stack_reader.hpp"

#include <png.h>
#include <tiffio.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <memory>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "volume/header_text.hpp"
#include "volume/voxel_data.hpp"

namespace forensim {
namespace {

struct Slice {
  int width = 0, height = 0;
  std::vector<float> values;
};

// libtiff reports through handlers; keep the last message for the InputError.
thread_local std::string t_tiff_message;

// The format attribute tells the compiler that `fmt` is libtiff's printf format (clang's -Wformat-nonliteral).
__attribute__((format(printf, 4, 0))) int tiff_error_handler(TIFF*, void*, const char* module, const char* fmt,
                                                             va_list ap) {
  char buffer[512];
  std::vsnprintf(buffer, sizeof(buffer), fmt, ap);
  t_tiff_message = std::string(module != nullptr ? module : "libtiff") + ": " + buffer;
  return 1;
}

int tiff_warning_handler(TIFF*, void*, const char*, const char*, va_list) {
  return 1;
}

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};

void append_tiff_pages(const std::filesystem::path& file, std::vector<Slice>& slices) {
  const std::string src = file.string();
  t_tiff_message.clear();
  TIFFOpenOptions* opts = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(opts, tiff_error_handler, nullptr);
  TIFFOpenOptionsSetWarningHandlerExtR(opts, tiff_warning_handler, nullptr);
  std::unique_ptr<TIFF, TiffCloser> tif(TIFFOpenExt(src.c_str(), "r", opts));
  TIFFOpenOptionsFree(opts);
  if (!tif) throw InputError(src, "", "not a readable TIFF: " + t_tiff_message);
  int page = 0;
  do {
    const std::string where = "page " + std::to_string(page);
    std::uint32_t w = 0, h = 0;
    std::uint16_t bits = 1, samples = 1, format = SAMPLEFORMAT_UINT;
    TIFFGetField(tif.get(), TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(tif.get(), TIFFTAG_IMAGELENGTH, &h);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_SAMPLESPERPIXEL, &samples);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_SAMPLEFORMAT, &format);
    require_input(samples == 1, src, where, "has " + std::to_string(samples) + " samples per pixel; need greyscale");
    require_input(bits == 8 || bits == 16, src, where,
                  "has " + std::to_string(bits) + " bits per sample; need 8 or 16");
    require_input(format == SAMPLEFORMAT_UINT || format == SAMPLEFORMAT_INT, src, where, "is not integer data");
    const std::int64_t sizes[3] = {w, h, 1};
    const std::uint64_t count = checked_voxel_count(sizes, src, where);
    const VoxelType type = bits == 8 ? (format == SAMPLEFORMAT_INT ? VoxelType::int8 : VoxelType::uint8)
                                     : (format == SAMPLEFORMAT_INT ? VoxelType::int16 : VoxelType::uint16);
    const std::size_t bps = bits / 8;
    // Compressed data can expand without bound, but libtiff decodes into our buffer of the declared size only;
    // still refuse sizes far beyond what the file could describe.
    const std::uint64_t file_size = std::filesystem::file_size(file);
    require_input(count * bps <= file_size * 1100 + 65536, src, where,
                  std::to_string(w) + " x " + std::to_string(h) + " pixels cannot fit in a file of " +
                      std::to_string(file_size) + " bytes");
    std::vector<unsigned char> pixels(count * bps);
    if (TIFFIsTiled(tif.get())) {
      std::uint32_t tw = 0, th = 0;
      TIFFGetField(tif.get(), TIFFTAG_TILEWIDTH, &tw);
      TIFFGetField(tif.get(), TIFFTAG_TILELENGTH, &th);
      require_input(tw > 0 && th > 0, src, where, "tile size is zero");
      const tmsize_t tile_bytes = TIFFTileSize(tif.get());
      require_input(tile_bytes > 0 && std::uint64_t(tile_bytes) == std::uint64_t(tw) * th * bps, src, where,
                    "unexpected tile size");
      std::vector<unsigned char> tile(static_cast<std::size_t>(tile_bytes));
      for (std::uint32_t y0 = 0; y0 < h; y0 += th) {
        for (std::uint32_t x0 = 0; x0 < w; x0 += tw) {
          if (TIFFReadTile(tif.get(), tile.data(), x0, y0, 0, 0) < 0) {
            throw InputError(src, where, "cannot decode a tile: " + t_tiff_message);
          }
          for (std::uint32_t y = y0; y < std::min(h, y0 + th); ++y) {
            const std::size_t n = std::size_t(std::min(w, x0 + tw) - x0) * bps;
            std::copy_n(tile.data() + std::size_t(y - y0) * tw * bps, n,
                        pixels.data() + (std::size_t(y) * w + x0) * bps);
          }
        }
      }
    } else {
      const tmsize_t line = TIFFScanlineSize(tif.get());
      require_input(line > 0 && std::uint64_t(line) == std::uint64_t(w) * bps, src, where, "unexpected scanline size");
      for (std::uint32_t y = 0; y < h; ++y) {
        if (TIFFReadScanline(tif.get(), pixels.data() + std::size_t(y) * w * bps, y, 0) < 0) {
          throw InputError(src, where + " row " + std::to_string(y), "cannot decode: " + t_tiff_message);
        }
      }
    }
    Slice s;
    s.width = int(w);
    s.height = int(h);
    s.values.resize(count);
    // libtiff returns samples in the machine's byte order.
    decode_voxels(pixels.data(), count, type, std::endian::native == std::endian::big, s.values.data());
    slices.push_back(std::move(s));
    ++page;
  } while (TIFFReadDirectory(tif.get()));
}

Slice read_png_slice(const std::filesystem::path& file) {
  const std::string src = file.string();
  const std::string bytes = read_file(file, std::size_t{1} << 31);
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    throw InputError(src, "", std::string("not a readable PNG: ") + image.message);
  }
  struct Guard {
    png_image* img;
    ~Guard() { png_image_free(img); }
  } guard{&image};
  require_input((image.format & PNG_FORMAT_FLAG_COLOR) == 0, src, "IHDR", "is a colour image; need greyscale");
  const std::int64_t sizes[3] = {image.width, image.height, 1};
  const std::uint64_t count = checked_voxel_count(sizes, src, "IHDR");
  require_input(count <= bytes.size() * std::uint64_t{1100} + 65536, src, "IHDR",
                "declares more pixels than the file can hold");
  // 16-bit files are read as stored (libpng treats them as linear); 8-bit as stored grey.
  const bool sixteen = (image.format & PNG_FORMAT_FLAG_LINEAR) != 0;
  image.format = sixteen ? PNG_FORMAT_LINEAR_Y : PNG_FORMAT_GRAY;
  Slice s;
  s.width = int(image.width);
  s.height = int(image.height);
  s.values.resize(count);
  if (sixteen) {
    std::vector<std::uint16_t> px(count);
    if (!png_image_finish_read(&image, nullptr, px.data(), 0, nullptr)) {
      throw InputError(src, "", std::string("cannot decode: ") + image.message);
    }
    std::transform(px.begin(), px.end(), s.values.begin(), [](std::uint16_t v) { return float(v); });
  } else {
    std::vector<std::uint8_t> px(count);
    if (!png_image_finish_read(&image, nullptr, px.data(), 0, nullptr)) {
      throw InputError(src, "", std::string("cannot decode: ") + image.message);
    }
    std::transform(px.begin(), px.end(), s.values.begin(), [](std::uint8_t v) { return float(v); });
  }
  return s;
}

bool glob_match(const char* p, const char* s) {
  // Iterative '*' matcher with backtracking to the last star.
  const char* star = nullptr;
  const char* after = nullptr;
  while (*s != '\0') {
    if (*p == '?' || *p == *s) {
      ++p;
      ++s;
    } else if (*p == '*') {
      star = p++;
      after = s;
    } else if (star != nullptr) {
      p = star + 1;
      s = ++after;
    } else {
      return false;
    }
  }
  while (*p == '*') ++p;
  return *p == '\0';
}

bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      std::string da = a.substr(i, ie - i), db = b.substr(j, je - j);
      da.erase(0, std::min(da.find_first_not_of('0'), da.size()));
      db.erase(0, std::min(db.find_first_not_of('0'), db.size()));
      if (da.size() != db.size()) return da.size() < db.size();
      if (da != db) return da < db;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace

ScalarGrid read_image_stack(const std::vector<std::filesystem::path>& files, const Vec3& spacing_mm) {
  require_input(!files.empty(), "image stack", "", "no slice files given");
  require_input(spacing_mm.allFinite() && (spacing_mm.array() > 0.0).all(), "image stack", "spacing",
                "must be three positive finite numbers (mm)");
  std::vector<Slice> slices;
  std::vector<std::filesystem::path> origin_file;
  std::uint64_t total = 0;
  for (const auto& file : files) {
    std::ifstream probe(file, std::ios::binary);
    if (!probe) throw IoError(file.string(), "cannot open for reading");
    unsigned char magic[8] = {};
    probe.read(reinterpret_cast<char*>(magic), 8);
    probe.close();
    const bool is_png = magic[0] == 0x89 && magic[1] == 'P' && magic[2] == 'N' && magic[3] == 'G';
    const bool is_tiff = (magic[0] == 'I' && magic[1] == 'I') || (magic[0] == 'M' && magic[1] == 'M');
    require_input(is_png || is_tiff, file.string(), "byte 0", "is neither a PNG nor a TIFF image");
    const std::size_t before = slices.size();
    if (is_png) {
      slices.push_back(read_png_slice(file));
    } else {
      append_tiff_pages(file, slices);
    }
    for (std::size_t s = before; s < slices.size(); ++s) {
      origin_file.push_back(file);
      require_input(slices[s].width == slices[0].width && slices[s].height == slices[0].height, file.string(), "",
                    std::to_string(slices[s].width) + " x " + std::to_string(slices[s].height) +
                        " pixels differ from the first slice's " + std::to_string(slices[0].width) + " x " +
                        std::to_string(slices[0].height));
      total += slices[s].values.size();
      require_input(total <= k_max_grid_voxels, file.string(), "", "the stack exceeds the voxel limit");
    }
  }
  ScalarGrid grid = ScalarGrid::filled(slices[0].width, slices[0].height, int(slices.size()));
  grid.spacing = spacing_mm;
  const std::size_t per_slice = slices[0].values.size();
  for (std::size_t k = 0; k < slices.size(); ++k) {
    std::copy(slices[k].values.begin(), slices[k].values.end(), grid.values.begin() + std::ptrdiff_t(k * per_slice));
  }
  return grid;
}

std::vector<std::filesystem::path> list_matching_files(const std::filesystem::path& folder,
                                                       const std::string& pattern) {
  std::error_code ec;
  std::filesystem::directory_iterator it(folder, ec);
  if (ec) throw IoError(folder.string(), "cannot list the folder: " + ec.message());
  std::vector<std::filesystem::path> files;
  for (const auto& entry : it) {
    if (!entry.is_regular_file(ec)) continue;
    const std::string name = entry.path().filename().string();
    if (glob_match(pattern.c_str(), name.c_str())) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end(),
            [](const auto& a, const auto& b) { return natural_less(a.filename().string(), b.filename().string()); });
  return files;
}

ScalarGrid read_image_stack(const std::filesystem::path& folder, const std::string& pattern, const Vec3& spacing_mm) {
  const std::vector<std::filesystem::path> files = list_matching_files(folder, pattern);
  require_input(!files.empty(), folder.string(), "pattern", "no file matches '" + pattern + "'");
  return read_image_stack(files, spacing_mm);
}

}  // namespace forensim
