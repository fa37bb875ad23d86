#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "image/color.hpp"
#include "image/colormap.hpp"

using namespace forensim;

TEST(Color, SrgbRoundTrip) {
  for (int i = 0; i <= 1000; ++i) {
    const float v = static_cast<float>(i) / 1000.0f;
    EXPECT_NEAR(srgb_to_linear(linear_to_srgb(v)), v, 2e-6f) << v;
    EXPECT_NEAR(linear_to_srgb(srgb_to_linear(v)), v, 2e-6f) << v;
  }
}

TEST(Color, SrgbKnownValues) {
  EXPECT_NEAR(linear_to_srgb(0.5f), 0.7354f, 1e-4f);  // IEC 61966-2-1
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.2140f, 1e-4f);
  EXPECT_EQ(linear_to_srgb(-1.0f), 0.0f);
  EXPECT_EQ(linear_to_srgb(3.0f), 1.0f);
}

TEST(Color, ImageConversionKeepsAlphaAndTags) {
  Image image(1, 1, 4);
  image.set_rgba(0, 0, Vec4f(0.5f, 0.5f, 0.5f, 0.5f));
  const Image s = to_srgb(image);
  EXPECT_EQ(s.encoding(), PixelEncoding::srgb);
  EXPECT_NEAR(s.at(0, 0, 0), 0.7354f, 1e-4f);
  EXPECT_EQ(s.at(0, 0, 3), 0.5f);
  const Image back = to_linear(s);
  EXPECT_NEAR(back.at(0, 0, 0), 0.5f, 1e-5f);
  Image data(1, 1, 1, 0.5f, PixelEncoding::data);
  EXPECT_EQ(to_srgb(data).at(0, 0), 0.5f);
}

TEST(Colormap, ViridisEndpointsMatchMatplotlib) {
  const Colormap map(ColormapName::viridis);
  const Vec3f lo = map.sample_srgb(0.0), hi = map.sample_srgb(1.0);
  EXPECT_NEAR(lo[0], 0.267f, 0.02f);
  EXPECT_NEAR(lo[1], 0.005f, 0.02f);
  EXPECT_NEAR(lo[2], 0.329f, 0.02f);
  EXPECT_NEAR(hi[0], 0.993f, 0.02f);
  EXPECT_NEAR(hi[1], 0.906f, 0.02f);
  EXPECT_NEAR(hi[2], 0.144f, 0.02f);
}

TEST(Colormap, SequentialMapsGetLighter) {
  for (ColormapName name : {ColormapName::viridis, ColormapName::inferno, ColormapName::magma, ColormapName::grey}) {
    const Colormap map(name);
    float previous = -1.0f;
    for (int i = 0; i <= 20; ++i) {
      const Vec3f c = map.sample(i / 20.0);
      const float luminance = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
      EXPECT_GT(luminance, previous - 1e-3f) << to_string(name) << " at " << i;
      previous = luminance;
    }
  }
}

TEST(Colormap, DivergingIsBlueNeutralRed) {
  const Colormap map(ColormapName::blue_white_red);
  const Vec3f lo = map.sample_srgb(0), mid = map.sample_srgb(0.5), hi = map.sample_srgb(1);
  EXPECT_GT(lo[2], lo[0]);
  EXPECT_GT(hi[0], hi[2]);
  EXPECT_NEAR(mid[0], mid[2], 0.01f);
  EXPECT_GT(mid[1], 0.8f);
}

TEST(Colormap, ByNameAndClamping) {
  EXPECT_EQ(Colormap::from_name("turbo").name(), ColormapName::turbo);
  EXPECT_THROW(Colormap::from_name("jet"), InputError);
  const Colormap map(ColormapName::inferno);
  EXPECT_EQ(map.sample(-5.0), map.sample(0.0));
  EXPECT_EQ(map.sample(std::nan("")), map.sample(0.0));
  EXPECT_EQ(map.map(10.0, 0.0, 10.0), map.sample(1.0));
}

TEST(Colormap, ColorizeMapsRangeToEnds) {
  Image values(3, 1, 1, 0.0f, PixelEncoding::data);
  values.at(0, 0) = 2.0f;
  values.at(1, 0) = 4.0f;
  values.at(2, 0) = std::nanf("");
  const Colormap map(ColormapName::magma);
  const Image picture = colorize(values, map, 2.0, 4.0);
  EXPECT_EQ(picture.encoding(), PixelEncoding::srgb);
  ASSERT_EQ(picture.channels(), 3);
  EXPECT_EQ(picture.rgba(0, 0).head<3>(), map.sample_srgb(0.0));
  EXPECT_EQ(picture.rgba(1, 0).head<3>(), map.sample_srgb(1.0));
  EXPECT_EQ(picture.rgba(2, 0).head<3>(), Vec3f(0.5f, 0.5f, 0.5f));
}
