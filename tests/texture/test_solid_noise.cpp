#include <gtest/gtest.h>

#include <cmath>

#include "texture/solid_noise.hpp"

using namespace forensim;

TEST(GradientNoise3, IsZeroOnTheLatticeAndBounded) {
  const GradientNoise3 noise(7);
  EXPECT_DOUBLE_EQ(noise.evaluate(Vec3(3, -2, 5)), 0.0);
  double lo = 1e9, hi = -1e9, sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Vec3 p(0.137 * i, 0.0713 * i + 0.3, std::sin(0.01 * i) * 40.0);
    const double v = noise.evaluate(p);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    sum += v;
  }
  EXPECT_GE(lo, -1.1);
  EXPECT_LE(hi, 1.1);
  EXPECT_GT(hi - lo, 0.8);             // not flat
  EXPECT_LT(std::abs(sum / n), 0.05);  // zero mean
}

TEST(GradientNoise3, IsContinuousWithFiniteDifferenceBoundedSlope) {
  const GradientNoise3 noise(1);
  const double h = 1e-5;
  for (int i = 0; i < 200; ++i) {
    const Vec3 p(0.31 * i, 1.7 + 0.05 * i, -0.23 * i);
    EXPECT_LT(std::abs(noise.evaluate(p + Vec3(h, h, h)) - noise.evaluate(p)), 10.0 * h);
  }
}

TEST(GradientNoise3, SeedChangesTheFieldAndIsDeterministic) {
  const GradientNoise3 a(1), b(2), a2(1);
  const Vec3 p(0.5, 1.25, 2.75);
  EXPECT_EQ(a.evaluate(p), a2.evaluate(p));
  EXPECT_NE(a.evaluate(p), b.evaluate(p));
  EXPECT_NEAR(a.fractal(p, 1), a.evaluate(p), 1e-15);
}
