#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "image/png_io.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

Image pattern(int w, int h, int channels, int levels, PixelEncoding encoding) {
  Image image(w, h, channels, 0.0f, encoding);
  int k = 0;
  for (float& v : image.data()) v = static_cast<float>((k++ * 37) % (levels + 1)) / static_cast<float>(levels);
  return image;
}

}  // namespace

TEST(PngIo, EightBitRoundTripIsExactForEveryLayout) {
  const auto dir = test::scratch_dir("png8");
  for (int channels = 1; channels <= 4; ++channels) {
    const Image image = pattern(13, 7, channels, 255, PixelEncoding::data);
    write_png(dir / "a.png", image);
    const Image back = read_png(dir / "a.png", PngTransfer::identity);
    ASSERT_EQ(back.channels(), channels);
    ASSERT_EQ(back.width(), 13);
    ASSERT_EQ(back.height(), 7);
    for (std::size_t i = 0; i < image.data().size(); ++i) EXPECT_FLOAT_EQ(back.data()[i], image.data()[i]);
  }
}

TEST(PngIo, SixteenBitRoundTripIsExact) {
  const auto dir = test::scratch_dir("png16");
  const Image image = pattern(9, 5, 4, 65535, PixelEncoding::data);
  write_png(dir / "b.png", image, {16, PngTransfer::automatic, 6});
  const Image back = read_png(dir / "b.png", PngTransfer::identity);
  for (std::size_t i = 0; i < image.data().size(); ++i) EXPECT_NEAR(back.data()[i], image.data()[i], 1e-7f);
}

TEST(PngIo, LinearImageIsSrgbEncodedAndDecodedBack) {
  const Image image = pattern(16, 4, 3, 1000, PixelEncoding::linear);
  const Image back = decode_png(encode_png(image));
  EXPECT_EQ(back.encoding(), PixelEncoding::linear);
  // 8-bit sRGB quantisation: half a code value in the encoded domain is at most 0.5/255 * 2.27 (the
  // slope of the decoding curve at 1) = 0.0045 in linear.
  for (std::size_t i = 0; i < image.data().size(); ++i) EXPECT_NEAR(back.data()[i], image.data()[i], 4.5e-3f);
  // Stored bytes are sRGB-encoded: linear 0.5 is stored as code 188.
  Image grey(1, 1, 1, 0.5f);
  const Image raw = decode_png(encode_png(grey), "grey", PngTransfer::identity);
  EXPECT_NEAR(raw.at(0, 0) * 255.0f, 188.0f, 0.01f);
}

TEST(PngIo, AlphaIsNeverTransferEncoded) {
  Image image(1, 1, 4, 0.5f);
  const Image raw = decode_png(encode_png(image), "alpha", PngTransfer::identity);
  EXPECT_NEAR(raw.at(0, 0, 3) * 255.0f, 128.0f, 0.01f);
}

TEST(PngIo, EncodedBytesStartWithSignature) {
  const std::string bytes = encode_png(Image(2, 2, 3, 1.0f));
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
}

TEST(PngIo, RejectsBadOptionsAndEmptyImages) {
  EXPECT_THROW(encode_png(Image()), InputError);
  EXPECT_THROW(encode_png(Image(1, 1, 1), {12, PngTransfer::automatic, 6}), InputError);
  EXPECT_THROW(read_png(test::scratch_dir("missing") / "nope.png"), IoError);
}

TEST(PngIo, HandMadeGoodFileReads) {
  const Image image = read_png(test::tests_dir() / "corpus/image/good_4x4.png", PngTransfer::identity);
  ASSERT_EQ(image.width(), 4);
  ASSERT_EQ(image.channels(), 3);
  EXPECT_NEAR(image.at(3, 3, 2) * 255.0f, 30.0f, 1e-3f);
}

TEST(PngIo, HostileCorpusThrowsInputError) {
  const auto corpus = test::tests_dir() / "corpus/image";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    if (entry.path().extension() != ".png" || entry.path().filename().string().starts_with("good_")) continue;
    ++count;
    EXPECT_THROW(read_png(entry.path()), InputError) << entry.path();
  }
  EXPECT_GE(count, 10);
}

TEST(PngIo, EveryTruncationOfAValidFileThrowsOrReads) {
  const std::string bytes = encode_png(pattern(7, 5, 4, 255, PixelEncoding::data));
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    // A cut inside the image data must be an InputError; a cut inside the trailing IEND chunk may still
    // decode every pixel. Never a crash.
    try {
      const Image image = decode_png(std::string_view(bytes).substr(0, n), "cut");
      EXPECT_GE(n, bytes.size() - 12) << n;
      EXPECT_EQ(image.width(), 7);
    } catch (const InputError&) {
    }
  }
}

TEST(PngIo, PaletteWithTransparencyAndLowBitDepthsExpand) {
  const auto corpus = test::tests_dir() / "corpus/image";
  const Image palette = read_png(corpus / "good_palette_2bit.png", PngTransfer::identity);
  ASSERT_EQ(palette.channels(), 4);
  ASSERT_EQ(palette.width(), 4);
  // Row 0 holds indices 0, 1, 2, 3: red, half-transparent green, blue, white.
  EXPECT_EQ(palette.rgba(0, 0), Vec4f(1, 0, 0, 1));
  EXPECT_NEAR(palette.at(1, 0, 3), 128.0f / 255.0f, 1e-6f);
  EXPECT_EQ(palette.rgba(2, 0), Vec4f(0, 0, 1, 1));
  EXPECT_EQ(palette.rgba(3, 1), Vec4f(1, 0, 0, 1));  // row 1 reversed
  const Image grey = read_png(corpus / "good_grey_1bit.png", PngTransfer::identity);
  ASSERT_EQ(grey.channels(), 1);
  EXPECT_EQ(grey.at(0, 0), 1.0f);
  EXPECT_EQ(grey.at(1, 0), 0.0f);
  EXPECT_EQ(grey.at(1, 1), 1.0f);
}
