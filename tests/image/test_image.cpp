#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "core/error.hpp"
#include "image/image.hpp"

using namespace forensim;

TEST(Image, ConstructorRejectsBadSizes) {
  EXPECT_THROW(Image(-1, 4, 3), InputError);
  EXPECT_THROW(Image(4, 4, 5), InputError);
  EXPECT_THROW(Image(4, 4, 0), InputError);
  EXPECT_THROW(Image(1 << 15, 1 << 15, 1), InputError);  // 2^30 pixels > cap
}

TEST(Image, RowMajorTopLeftOrigin) {
  Image image(3, 2, 2);
  image.at(2, 1, 1) = 7.0f;
  EXPECT_EQ(image.data()[(1 * 3 + 2) * 2 + 1], 7.0f);
}

TEST(Image, BilinearSampleInterpolatesBetweenCentres) {
  Image image(2, 1, 1);
  image.at(0, 0) = 0.0f;
  image.at(1, 0) = 1.0f;
  EXPECT_FLOAT_EQ(image.sample(0.5, 0.5, 0), 0.0f);
  EXPECT_FLOAT_EQ(image.sample(1.0, 0.5, 0), 0.5f);
  EXPECT_FLOAT_EQ(image.sample(1.5, 0.5, 0), 1.0f);
  EXPECT_FLOAT_EQ(image.sample(5.0, 0.5, 0, WrapMode::clamp), 1.0f);
  // Wrapping: halfway between the last and the first pixel.
  EXPECT_FLOAT_EQ(image.sample(2.0, 0.5, 0, WrapMode::wrap), 0.5f);
}

TEST(Image, SampleUvHasVUp) {
  Image image(1, 2, 1);
  image.at(0, 0) = 1.0f;  // top row
  image.at(0, 1) = 0.0f;
  EXPECT_NEAR(image.sample_uv(Vec2(0.5, 0.99), WrapMode::clamp)[0], 1.0f, 1e-6);
  EXPECT_NEAR(image.sample_uv(Vec2(0.5, 0.01), WrapMode::clamp)[0], 0.0f, 1e-6);
}

TEST(Image, BoxDownsamplePreservesMean) {
  Image image(9, 7, 1);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) image.at(x, y) = static_cast<float>((x * 31 + y * 17) % 11);
  const Image small = image.resized(4, 3);
  const auto mean = [](const Image& i) {
    return std::accumulate(i.data().begin(), i.data().end(), 0.0) / static_cast<double>(i.data().size());
  };
  EXPECT_NEAR(mean(small), mean(image), 1e-4);
}

TEST(Image, UpsampleOfConstantIsConstantAndCornersKept) {
  Image image(2, 2, 3, 0.25f);
  const Image big = image.resized(7, 5);
  for (float v : big.data()) EXPECT_NEAR(v, 0.25f, 1e-6);
  Image ramp(2, 1, 1);
  ramp.at(1, 0) = 1.0f;
  const Image wide = ramp.resized(8, 1);
  EXPECT_FLOAT_EQ(wide.at(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(wide.at(7, 0), 1.0f);
  for (int x = 1; x < 8; ++x) EXPECT_GE(wide.at(x, 0), wide.at(x - 1, 0));
}

TEST(Image, CropAndPasteRoundTrip) {
  Image image(6, 5, 4);
  for (std::size_t i = 0; i < image.data().size(); ++i) image.data()[i] = static_cast<float>(i);
  const Image block = image.crop(2, 1, 3, 3);
  ASSERT_EQ(block.width(), 3);
  EXPECT_EQ(block.at(0, 0, 2), image.at(2, 1, 2));
  Image canvas(6, 5, 4);
  canvas.paste(block, 2, 1);
  EXPECT_EQ(canvas.at(4, 3, 3), image.at(4, 3, 3));
  EXPECT_EQ(canvas.at(1, 1, 0), 0.0f);
  // Clipped crop and paste stay in bounds.
  EXPECT_EQ(image.crop(4, 4, 10, 10).width(), 2);
  canvas.paste(block, -2, 4);
}

TEST(Image, AlphaBlendPaste) {
  Image canvas(1, 1, 3, 0.0f);
  Image overlay(1, 1, 4);
  overlay.set_rgba(0, 0, Vec4f(1, 1, 1, 0.25f));
  canvas.paste(overlay, 0, 0, true);
  EXPECT_FLOAT_EQ(canvas.at(0, 0, 1), 0.25f);
}

TEST(Image, ChannelConversion) {
  Image rgb(1, 1, 3);
  rgb.set_rgba(0, 0, Vec4f(1, 1, 1, 1));
  const Image grey = rgb.with_channels(1);
  EXPECT_NEAR(grey.at(0, 0), 1.0f, 1e-6);
  const Image rgba = grey.with_channels(4);
  EXPECT_FLOAT_EQ(rgba.at(0, 0, 3), 1.0f);
}
