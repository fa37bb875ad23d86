// The generated dermis look-up texture: monotone along its axes as designed, the hydrated half equal to the
// livor colours, a green stage that exists only with biliverdin, determinism, file round trips, bad settings.

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "image/exr_io.hpp"
#include "image/png_io.hpp"
#include "skin/dermis_lut.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {
double luminance(const Vec3& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}
}  // namespace

TEST(DermisLut, EveryChannelDarkensWithSaturation) {
  const DermisLut lut;
  for (int j = 0; j < lut.size_v(); ++j)
    for (int i = 1; i < lut.size_u(); ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_LT(lut.texel(i, j)[c], lut.texel(i - 1, j)[c])
            << "u texel " << i << ", v texel " << j << ", channel " << c;
}

TEST(DermisLut, LuminanceFallsAsTheHemoglobinDegrades) {
  const DermisLut lut;
  for (int i = 0; i < lut.size_u(); ++i)
    for (int j = lut.size_v() - 1; j > 0; --j)
      ASSERT_LT(luminance(lut.texel(i, j - 1)), luminance(lut.texel(i, j))) << "u texel " << i << ", v texel " << j - 1;
}

TEST(DermisLut, HydratedHalfIsTheLivorColour) {
  const DermisLut lut;
  const int half = (lut.size_v() - 1) / 2;
  for (int j = half; j < lut.size_v(); ++j) {
    const double o = 2.0 * j / (lut.size_v() - 1) - 1.0;
    for (int i = 0; i < lut.size_u(); i += 7) {
      const double s = static_cast<double>(i) / (lut.size_u() - 1);
      EXPECT_LT((lut.texel(i, j) - livor_dermis_colour(s, o)).norm(), 1e-12) << i << " " << j;
    }
  }
  // Deoxygenated blood is darker in red than oxygenated blood: the bluish purple of hypostasis.
  EXPECT_LT(livor_dermis_colour(1.0, 0.0)[0], livor_dermis_colour(1.0, 1.0)[0] - 0.1);
}

TEST(DermisLut, CompositionConservesTheHeme) {
  for (double d = 0.0; d <= 1.0; d += 0.05) {
    const DermisComposition c = dermis_composition(0.5, d);
    EXPECT_NEAR(c.oxy + c.deoxy + c.met + c.biliverdin + c.bilirubin, 1.0, 1e-12) << d;
    EXPECT_GE(std::min({c.oxy, c.deoxy, c.met, c.biliverdin, c.bilirubin}), 0.0);
    EXPECT_NEAR(c.dryness, std::max(0.0, 1.0 - 2.0 * d), 1e-12);
  }
}

TEST(DermisLut, GreenStageComesFromBiliverdin) {
  auto greenest = [](const DermisLut& lut) {
    double best = 0.0;
    for (int j = 0; j < (lut.size_v() - 1) / 2; ++j) {
      const Vec3& c = lut.texel(lut.size_u() - 1, j);
      best = std::max(best, c[1] / c[0]);
    }
    return best;
  };
  const DermisLut with_green;
  DermisLutSettings no_green_settings;
  no_green_settings.heme_to_biliverdin = 0.0;
  const DermisLut no_green(no_green_settings);
  const Vec3 livor = with_green.sample(1.0, 0.5), dried = with_green.sample(1.0, 0.0);
  // The green stage is greener than hypostasis and than the dried end, and greener than without biliverdin.
  EXPECT_GT(greenest(with_green), 1.05 * livor[1] / livor[0]);
  EXPECT_GT(greenest(with_green), 1.05 * dried[1] / dried[0]);
  EXPECT_GT(greenest(with_green), 1.05 * greenest(no_green));
  // Fully dried blood-rich dermis is brown: red over green over blue.
  EXPECT_GT(dried[0], dried[1]);
  EXPECT_GT(dried[1], 1.5 * dried[2]);
}

TEST(DermisLut, IsDeterministic) {
  const DermisLut a, b;
  for (int j = 0; j < a.size_v(); ++j)
    for (int i = 0; i < a.size_u(); ++i) ASSERT_EQ(a.texel(i, j), b.texel(i, j));
}

TEST(DermisLut, BilinearSampleHitsTexelsAndInterpolates) {
  const DermisLut lut;
  EXPECT_LT((lut.sample(0.0, 1.0) - lut.texel(0, lut.size_v() - 1)).norm(), 1e-15);
  EXPECT_LT((lut.sample(1.0, 0.0) - lut.texel(lut.size_u() - 1, 0)).norm(), 1e-15);
  const double du = 1.0 / (lut.size_u() - 1);
  const Vec3 mid = lut.sample(2.5 * du, 0.5);
  const int half = (lut.size_v() - 1) / 2;
  EXPECT_LT((mid - 0.5 * (lut.texel(2, half) + lut.texel(3, half))).norm(), 1e-12);
}

TEST(DermisLut, WritesExrAndPngThatReadBack) {
  const DermisLut lut;
  const auto dir = test::scratch_dir("dermis_lut");
  write_dermis_lut(lut, dir / "lut.exr");
  const Image exr = read_exr(dir / "lut.exr");
  ASSERT_EQ(exr.width(), lut.size_u());
  ASSERT_EQ(exr.height(), lut.size_v());
  // Row 0 is v = 1 (fresh), the last row v = 0 (dried).
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(exr.at(5, 0, c), static_cast<float>(lut.texel(5, lut.size_v() - 1)[c]));
    EXPECT_FLOAT_EQ(exr.at(5, lut.size_v() - 1, c), static_cast<float>(lut.texel(5, 0)[c]));
  }
  write_dermis_lut(lut, dir / "lut.png", 4);
  const Image png = read_png(dir / "lut.png");
  ASSERT_EQ(png.width(), 4 * lut.size_u());
  EXPECT_NEAR(png.at(4 * 9 + 1, 4 * 20 + 2, 0), lut.texel(9, lut.size_v() - 1 - 20)[0], 0.01);
  EXPECT_THROW(write_dermis_lut(lut, dir / "lut.jpg"), InputError);
}

TEST(DermisLut, RejectsBadSettings) {
  DermisLutSettings s;
  s.size_v = 64;  // even: v = 1/2 would fall between rows
  EXPECT_THROW(DermisLut{s}, InputError);
  s = {};
  s.blood_fraction_min = 0.5;
  s.blood_fraction_max = 0.1;
  EXPECT_THROW(DermisLut{s}, InputError);
  s = {};
  s.bilirubin_onset = 0.9;
  EXPECT_THROW(DermisLut{s}, InputError);
  s = {};
  s.water_fraction = 1.0;
  EXPECT_THROW(DermisLut{s}, InputError);
}
