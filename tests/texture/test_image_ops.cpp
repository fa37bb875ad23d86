#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/random.hpp"
#include "texture/image_ops.hpp"

using namespace forensim;

TEST(CubicInterpolate, InterpolatesEndsAndReproducesLines) {
  EXPECT_DOUBLE_EQ(cubic_interpolate(3, 1, 7, 2, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(cubic_interpolate(3, 1, 7, 2, 1.0), 7.0);
  // Eq. 3.4 as printed: (0, 2, 4, 6) gives p = 4, q = -6, r = 4, so 4t^3 - 6t^2 + 4t + 2 (not exact for lines:
  // r = v2 - v0 is twice the Catmull-Rom tangent), symmetric about t = 0.5 for symmetric data.
  for (double t = 0.0; t <= 1.0; t += 0.125)
    EXPECT_NEAR(cubic_interpolate(0, 2, 4, 6, t), 4 * t * t * t - 6 * t * t + 4 * t + 2, 1e-12);
  EXPECT_DOUBLE_EQ(cubic_interpolate(0, 2, 4, 6, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(cubic_interpolate(5, 5, 5, 5, 0.3), 5.0);  // constants are kept
}

TEST(SampleBicubic, EqualsPixelsAtCentresAndWraps) {
  Image image(5, 4, 1);
  RandomStream rng(3, 0);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) image.at(x, y) = static_cast<float>(rng.uniform());
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) {
      EXPECT_FLOAT_EQ(sample_bicubic(image, x + 0.5, y + 0.5, 0, WrapMode::clamp), image.at(x, y));
      EXPECT_FLOAT_EQ(sample_bicubic(image, x + 0.5, y + 0.5, 0, WrapMode::wrap), image.at(x, y));
    }
  // Wrapping: shifting by a whole period gives the same value between centres too.
  EXPECT_NEAR(sample_bicubic(image, 1.3, 2.7, 0, WrapMode::wrap), sample_bicubic(image, 6.3, -1.3, 0, WrapMode::wrap),
              1e-6);
  EXPECT_NEAR(sample_bilinear(image, 1.3, 2.7, 0, WrapMode::wrap), sample_bilinear(image, 6.3, 6.7, 0, WrapMode::wrap),
              1e-6);
  EXPECT_EQ(sample_bicubic(image, std::nan(""), 1.0, 0), 0.0f);
  EXPECT_EQ(wrap_pixel_index(-1, 5, WrapMode::wrap), 4);
  EXPECT_EQ(wrap_pixel_index(-1, 5, WrapMode::clamp), 0);
  EXPECT_EQ(wrap_pixel_index(12, 5, WrapMode::clamp), 4);
}

TEST(Blend, ModesMatchTheirFormulas) {
  const Vec4f a(0.2f, 0.6f, 0.5f, 1.0f), b(0.5f, 0.3f, 0.9f, 1.0f);
  const Vec4f m = blend_multiply(a, b), s = blend_screen(a, b), o = blend_overlay(a, b);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(m[c], a[c] * b[c]);
    EXPECT_NEAR(s[c], 1.0f - (1.0f - a[c]) * (1.0f - b[c]), 1e-6f);  // eq. 4.7 is screen
    EXPECT_NEAR(s[c], blend_screen(b, a)[c], 1e-6f);                 // commutative
    const float expected = a[c] < 0.5f ? 2 * a[c] * b[c] : 1 - 2 * (1 - a[c]) * (1 - b[c]);
    EXPECT_FLOAT_EQ(o[c], expected);
  }
  EXPECT_EQ(blend_lerp(a, b, 0.0f), a);
  EXPECT_EQ(blend_lerp(a, b, 1.0f), b);
}

TEST(Blend, ImagesAndMaskLerp) {
  Image upper(3, 2, 3, 0.8f), lower(3, 2, 3, 0.2f), mask(3, 2, 1, 0.0f);
  mask.at(1, 0) = 0.25f;
  mask.at(2, 1) = 1.0f;
  const Image mixed = lerp_by_mask(upper, lower, mask);  // eq. 4.5
  EXPECT_FLOAT_EQ(mixed.at(0, 0, 1), 0.8f);
  EXPECT_FLOAT_EQ(mixed.at(1, 0, 1), 0.8f * 0.75f + 0.2f * 0.25f);
  EXPECT_FLOAT_EQ(mixed.at(2, 1, 2), 0.2f);
  const Image product = blend_images(upper, lower, BlendMode::multiply);
  EXPECT_FLOAT_EQ(product.at(2, 1, 0), 0.16f);
  const Image red = multiply_color(upper, Vec4f(0.79f, 0.0f, 0.0f, 1.0f));
  EXPECT_FLOAT_EQ(red.at(0, 0, 0), 0.8f * 0.79f);
  EXPECT_FLOAT_EQ(red.at(0, 0, 1), 0.0f);
  EXPECT_THROW(lerp_by_mask(upper, Image(2, 2, 3), mask), InputError);
  EXPECT_THROW(blend_images(upper, Image(3, 3, 3), BlendMode::screen), InputError);
}
