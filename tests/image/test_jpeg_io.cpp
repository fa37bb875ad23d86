#include "image/jpeg_io.hpp"

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "image/png_io.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

void append_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

/// A smooth RGB test picture encoded as JPEG at high quality.
std::string gradient_jpeg(int w, int h) {
  std::string pixels(static_cast<std::size_t>(w * h * 3), '\0');
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      unsigned char* p = reinterpret_cast<unsigned char*>(&pixels[static_cast<std::size_t>((y * w + x) * 3)]);
      p[0] = static_cast<unsigned char>(255 * x / (w - 1));
      p[1] = static_cast<unsigned char>(255 * y / (h - 1));
      p[2] = 128;
    }
  std::string out;
  stbi_write_jpg_to_func(append_bytes, &out, w, h, 3, pixels.data(), 95);
  return out;
}

}  // namespace

TEST(Jpeg, DecodesToLinearColourCloseToTheSource) {
  const std::string bytes = gradient_jpeg(64, 32);
  const Image linear = decode_jpeg(bytes);
  ASSERT_EQ(linear.width(), 64);
  ASSERT_EQ(linear.height(), 32);
  ASSERT_EQ(linear.channels(), 3);
  const Image stored = decode_jpeg(bytes, "test", false);
  double worst = 0.0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      worst = std::max(worst, std::abs(stored.at(x, y, 0) - x / 63.0));
      worst = std::max(worst, std::abs(stored.at(x, y, 1) - y / 31.0));
    }
  EXPECT_LT(worst, 0.04) << "JPEG at quality 95 keeps a smooth gradient";
  // sRGB 0.5 decodes to about 0.214 linear.
  EXPECT_NEAR(linear.at(10, 10, 2), 0.2158f, 0.02f);
}

TEST(Jpeg, RejectsCorruptAndForeignData) {
  std::string bytes = gradient_jpeg(16, 16);
  EXPECT_THROW(decode_jpeg(bytes.substr(0, 40)), InputError);
  EXPECT_THROW(decode_jpeg("not a jpeg at all"), InputError);
  // A SOF header declaring 65535 x 65535 pixels.
  std::string huge = bytes;
  for (std::size_t i = 0; i + 8 < huge.size(); ++i) {
    if (static_cast<unsigned char>(huge[i]) == 0xFF && static_cast<unsigned char>(huge[i + 1]) == 0xC0) {
      huge[i + 5] = huge[i + 6] = huge[i + 7] = huge[i + 8] = static_cast<char>(0xFF);
      break;
    }
  }
  EXPECT_THROW(decode_jpeg(huge), InputError);
}

TEST(Jpeg, RejectsMorePixelsThanTheDataCanHold) {
  // A SOF header declaring 12000 x 12500 pixels (under the 2^28 limit) over a few hundred bytes: stb would decode
  // it as a 1.8 GB image (found by fuzz/jpeg).
  std::string bomb = gradient_jpeg(16, 16);
  for (std::size_t i = 0; i + 8 < bomb.size(); ++i) {
    if (static_cast<unsigned char>(bomb[i]) == 0xFF && static_cast<unsigned char>(bomb[i + 1]) == 0xC0) {
      bomb[i + 5] = static_cast<char>(12000 >> 8);
      bomb[i + 6] = static_cast<char>(12000 & 0xFF);
      bomb[i + 7] = static_cast<char>(12500 >> 8);
      bomb[i + 8] = static_cast<char>(12500 & 0xFF);
      break;
    }
  }
  try {
    decode_jpeg(bomb, "bomb.jpg");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("12500 x 12000 pixels, more than a JPEG of"), std::string::npos) << e.what();
  }
  // A blank picture, the best a JPEG compresses, stays well inside the bound.
  const int side = 1024;
  const std::string grey(static_cast<std::size_t>(side * side), '\x80');
  std::string blank;
  stbi_write_jpg_to_func(append_bytes, &blank, side, side, 1, grey.data(), 50);
  const Image decoded = decode_jpeg(blank, "blank.jpg", false);
  EXPECT_EQ(decoded.width(), side);
  EXPECT_NEAR(decoded.at(side / 2, side / 2, 0), 128.0f / 255.0f, 2.0f / 255.0f);
  EXPECT_LT(static_cast<double>(side) * side / static_cast<double>(blank.size()), 4096.0);
}

TEST(Jpeg, ReadImageChoosesTheDecoderByContent) {
  const auto dir = test::scratch_dir("jpeg");
  write_file_atomic(dir / "picture.png", gradient_jpeg(8, 8));  // a JPEG under a misleading name
  EXPECT_EQ(read_image(dir / "picture.png").width(), 8);
  write_png(dir / "real.png", Image(5, 3, 3, 0.5f));
  EXPECT_EQ(read_image(dir / "real.png").height(), 3);
  write_file_atomic(dir / "text.jpg", "hello");
  EXPECT_THROW(read_image(dir / "text.jpg"), InputError);
}

// Bytes in memory (a glTF's embedded texture): the decoder is chosen by content, and other data is refused
// naming its source.
TEST(Jpeg, DecodeImageChoosesTheDecoderByContent) {
  EXPECT_EQ(decode_image(gradient_jpeg(8, 4), "embedded").height(), 4);
  EXPECT_EQ(decode_image(encode_png(Image(5, 3, 3, 0.5f)), "embedded").width(), 5);
  try {
    decode_image("GIF89a", "head.glb texture");
    FAIL() << "GIF bytes were decoded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("head.glb texture"), std::string::npos) << e.what();
  }
}

TEST(Jpeg, ReadsAScannedHeadsColourMap) {
  FORENSIM_REQUIRE_DATA(path, "head-scan-lee-perry-smith/Map-COL.jpg");
  const Image map = read_jpeg(path);
  EXPECT_GE(map.width(), 1024);
  EXPECT_EQ(map.channels(), 3);
  double red = 0.0, blue = 0.0;
  for (int y = 0; y < map.height(); y += 16)
    for (int x = 0; x < map.width(); x += 16) red += map.at(x, y, 0), blue += map.at(x, y, 2);
  EXPECT_GT(red, blue) << "skin is redder than it is blue";
}
