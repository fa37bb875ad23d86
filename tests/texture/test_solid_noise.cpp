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

TEST(WorleyNoise3, DistancesMatchABruteForceSearchOfFeaturePoints) {
  const WorleyNoise3 noise(3, 0.5);
  for (int i = 0; i < 300; ++i) {
    const Vec3 p(0.37 * i - 20.0, 0.11 * i + 0.2, std::cos(0.05 * i) * 7.0);
    const CellularSample s = noise.evaluate(p);
    EXPECT_GE(s.f2, s.f1);
    EXPECT_NEAR((s.nearest - p).norm(), s.f1, 1e-12);
    // Feature points lie in their cell's central half with jitter 0.5, so F1 <= the distance to the own cell's
    // farthest possible point.
    EXPECT_LE(s.f1, std::sqrt(3.0) * 0.75 + 1e-12);
    // The nearest point belongs to the same cell id when found again from a point next to it.
    const CellularSample near_point = noise.evaluate(s.nearest + Vec3(1e-6, 0, 0));
    EXPECT_EQ(near_point.cell, s.cell);
    EXPECT_NEAR(near_point.f1, 1e-6, 1e-9);
  }
}

TEST(WorleyNoise3, IsContinuousDeterministicAndSeeded) {
  const WorleyNoise3 a(1), a2(1), b(2);
  double sum = 0.0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 p(0.173 * i, -0.07 * i, 0.031 * i + 2.0);
    const CellularSample s = a.evaluate(p);
    EXPECT_EQ(s.f1, a2.evaluate(p).f1);
    EXPECT_LT(std::abs(a.evaluate(p + Vec3(1e-6, 1e-6, 0)).f1 - s.f1), 2e-6);  // F1 is 1-Lipschitz
    sum += std::abs(s.f1 - b.evaluate(p).f1);
    const double v = a.cell_value(s.cell);
    EXPECT_GE(v, 0.0);
    EXPECT_LT(v, 1.0);
  }
  EXPECT_GT(sum, 10.0);  // another seed moves the points
}
