#include <gtest/gtest.h>
#include <png.h>
#include <tiffio.h>

#include <cstring>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "support/test_support.hpp"
#include "volume/image_stack_reader.hpp"
#include "volume/volume_reader.hpp"

using namespace forensim;

namespace {

// Writes a w x h greyscale TIFF page per entry of `pages` (8 or 16 bits), deflate-compressed, optionally tiled.
void write_tiff(const std::filesystem::path& path, int w, int h, int bits, const std::vector<std::vector<int>>& pages,
                bool tiled = false) {
  TIFF* tif = TIFFOpen(path.string().c_str(), "w");
  ASSERT_NE(tif, nullptr);
  for (const auto& values : pages) {
    TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, std::uint32_t(w));
    TIFFSetField(tif, TIFFTAG_IMAGELENGTH, std::uint32_t(h));
    TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, std::uint16_t(bits));
    TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, std::uint16_t(1));
    TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(tif, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
    const std::size_t bps = std::size_t(bits / 8);
    std::vector<unsigned char> bytes(values.size() * bps);
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (bits == 8) {
        bytes[i] = static_cast<unsigned char>(values[i]);
      } else {
        const std::uint16_t v = static_cast<std::uint16_t>(values[i]);
        std::memcpy(&bytes[2 * i], &v, 2);
      }
    }
    if (tiled) {
      TIFFSetField(tif, TIFFTAG_TILEWIDTH, std::uint32_t(16));
      TIFFSetField(tif, TIFFTAG_TILELENGTH, std::uint32_t(16));
      std::vector<unsigned char> tile(16 * 16 * bps, 0);
      for (int y0 = 0; y0 < h; y0 += 16) {
        for (int x0 = 0; x0 < w; x0 += 16) {
          std::fill(tile.begin(), tile.end(), 0);
          for (int y = y0; y < std::min(h, y0 + 16); ++y) {
            for (int x = x0; x < std::min(w, x0 + 16); ++x) {
              std::memcpy(&tile[(std::size_t(y - y0) * 16 + std::size_t(x - x0)) * bps],
                          &bytes[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * bps], bps);
            }
          }
          TIFFWriteTile(tif, tile.data(), std::uint32_t(x0), std::uint32_t(y0), 0, 0);
        }
      }
    } else {
      TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, std::uint32_t(2));
      for (int y = 0; y < h; ++y)
        TIFFWriteScanline(tif, &bytes[std::size_t(y) * std::size_t(w) * bps], std::uint32_t(y), 0);
    }
    TIFFWriteDirectory(tif);
  }
  TIFFClose(tif);
}

void write_png(const std::filesystem::path& path, int w, int h, int bits, const std::vector<int>& values) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = std::uint32_t(w);
  image.height = std::uint32_t(h);
  image.format = bits == 16 ? PNG_FORMAT_LINEAR_Y : PNG_FORMAT_GRAY;
  if (bits == 16) {
    std::vector<std::uint16_t> px(values.begin(), values.end());
    ASSERT_TRUE(png_image_write_to_file(&image, path.string().c_str(), 0, px.data(), 0, nullptr)) << image.message;
  } else {
    std::vector<std::uint8_t> px(values.begin(), values.end());
    ASSERT_TRUE(png_image_write_to_file(&image, path.string().c_str(), 0, px.data(), 0, nullptr)) << image.message;
  }
}

std::string numbered(const char* prefix, int k, const char* suffix) {
  std::string s = prefix;
  s += std::to_string(k);
  s += suffix;
  return s;
}

std::vector<int> ramp(int w, int h, int k, int scale) {
  std::vector<int> v(std::size_t(w * h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) v[std::size_t(y * w + x)] = (x + 3 * y + 7 * k) * scale % (scale == 1 ? 256 : 65536);
  }
  return v;
}

void expect_ramp(const ScalarGrid& g, int scale, int first_k = 0) {
  for (int k = 0; k < g.nz; ++k) {
    for (int y = 0; y < g.ny; ++y) {
      for (int x = 0; x < g.nx; ++x) {
        ASSERT_EQ(g.at(x, y, k), float((x + 3 * y + 7 * (k + first_k)) * scale % (scale == 1 ? 256 : 65536)))
            << x << " " << y << " " << k;
      }
    }
  }
}

}  // namespace

TEST(ImageStack, TiffSlices8And16BitNaturalOrder) {
  const auto dir = test::scratch_dir("tiff");
  const int w = 21, h = 18;
  for (int k = 0; k < 11; ++k) write_tiff(dir / numbered("slice_", k, ".tif"), w, h, 16, {ramp(w, h, k, 251)});
  const ScalarGrid g = read_image_stack(dir, "slice_*.tif", Vec3(0.3, 0.3, 0.8));
  EXPECT_EQ(g.nz, 11);  // slice_10 sorts after slice_9
  EXPECT_EQ(g.spacing, Vec3(0.3, 0.3, 0.8));
  expect_ramp(g, 251);
  // 8-bit, tiled, two pages in one file.
  write_tiff(dir / "tiled.tiff", w, h, 8, {ramp(w, h, 0, 1), ramp(w, h, 1, 1)}, true);
  const ScalarGrid t = read_image_stack(std::vector<std::filesystem::path>{dir / "tiled.tiff"}, Vec3::Ones());
  EXPECT_EQ(t.nz, 2);
  expect_ramp(t, 1);
}

TEST(ImageStack, PngSlices) {
  const auto dir = test::scratch_dir("png");
  const int w = 9, h = 5;
  std::vector<std::filesystem::path> files;
  for (int k = 0; k < 3; ++k) {
    files.push_back(dir / numbered("p", k, ".png"));
    write_png(files.back(), w, h, 16, ramp(w, h, k, 997));
  }
  expect_ramp(read_image_stack(files, Vec3(1, 1, 2)), 997);
  write_png(dir / "g.png", w, h, 8, ramp(w, h, 0, 1));
  expect_ramp(read_image_stack(std::vector<std::filesystem::path>{dir / "g.png"}, Vec3(1, 1, 2)), 1);
}

TEST(ImageStack, RejectsMismatchedAndBrokenSlices) {
  const auto dir = test::scratch_dir("stack_bad");
  write_png(dir / "a.png", 4, 4, 8, ramp(4, 4, 0, 1));
  write_png(dir / "b.png", 5, 4, 8, ramp(5, 4, 0, 1));
  EXPECT_THROW(read_image_stack(dir, "*.png", Vec3::Ones()), InputError);
  EXPECT_THROW(read_image_stack(dir, "none*.png", Vec3::Ones()), InputError);
  EXPECT_THROW(read_image_stack(std::vector<std::filesystem::path>{dir / "a.png"}, Vec3(1, 0, 1)), InputError);
  // A PNG cut in half and a file that is neither format.
  const std::string bytes = read_file(dir / "b.png");
  write_file_atomic(dir / "cut.png", bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(read_image_stack(std::vector<std::filesystem::path>{dir / "cut.png"}, Vec3::Ones()), InputError);
  write_file_atomic(dir / "text.tif", "hello");
  EXPECT_THROW(read_image_stack(std::vector<std::filesystem::path>{dir / "text.tif"}, Vec3::Ones()), InputError);
  write_file_atomic(dir / "bad.tif", std::string("II*\0garbage garbage garbage", 28));
  EXPECT_THROW(read_image_stack(std::vector<std::filesystem::path>{dir / "bad.tif"}, Vec3::Ones()), InputError);
}
