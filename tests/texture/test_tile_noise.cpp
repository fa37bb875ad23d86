#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/tile_noise.hpp"

using namespace forensim;

TEST(TilePerlinNoise, PeriodicZeroOnLatticeBoundedAndContinuous) {
  const int px = 5, py = 3;
  RandomStream rng(1, 0);
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 p(rng.uniform(-10, 10), rng.uniform(-10, 10));
    const double v = tile_perlin_noise(p, px, py, 4);
    EXPECT_NEAR(tile_perlin_noise(p + Vec2(px, 0), px, py, 4), v, 1e-12);
    EXPECT_NEAR(tile_perlin_noise(p + Vec2(-2 * px, 3 * py), px, py, 4), v, 1e-12);
    const double h = 1e-6;
    EXPECT_LT(std::abs(tile_perlin_noise(p + Vec2(h, h), px, py, 4) - v), 1e-4);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GE(lo, -1.0001);
  EXPECT_LE(hi, 1.0001);
  EXPECT_GT(hi - lo, 0.8);
  EXPECT_DOUBLE_EQ(tile_perlin_noise(Vec2(2, 1), px, py, 4), 0.0);
  EXPECT_THROW(tile_perlin_noise(Vec2(0.5, 0.5), 0, 1, 4), InputError);
}

TEST(TileWorleyNoise, MatchesBruteForceFeaturePoints) {
  // Recompute F1 and F2 against all feature points of a 3 x 3 tiling of the period, by brute force.
  const int px = 4, py = 3;
  const std::uint64_t seed = 8;
  std::vector<Vec2> features;
  for (int ty = -1; ty <= 1; ++ty)
    for (int tx = -1; tx <= 1; ++tx)
      for (int cy = 0; cy < py; ++cy)
        for (int cx = 0; cx < px; ++cx) {
          // The documented feature point of cell (cx, cy).
          const std::uint64_t key = static_cast<std::uint64_t>(cy) * px + static_cast<std::uint64_t>(cx);
          features.emplace_back(tx * px + cx + hash_uniform(seed, key, 1), ty * py + cy + hash_uniform(seed, key, 2));
        }
  RandomStream rng(2, 0);
  for (int i = 0; i < 500; ++i) {
    const Vec2 p(rng.uniform(0, px), rng.uniform(0, py));
    std::vector<double> d;
    for (const Vec2& f : features) d.push_back((f - p).norm());
    std::sort(d.begin(), d.end());
    const WorleyDistances w = tile_worley_noise(p, px, py, seed);
    ASSERT_NEAR(w.f1, d[0], 1e-12);
    ASSERT_NEAR(w.f2, d[1], 1e-12);
    // Periodic.
    const WorleyDistances shifted = tile_worley_noise(p + Vec2(3 * px, -py), px, py, seed);
    ASSERT_NEAR(shifted.f1, w.f1, 1e-9);
    ASSERT_NEAR(shifted.f2, w.f2, 1e-9);
  }
}

namespace {

// Largest step between neighbours inside the image, and across the wrap (right edge to left, bottom to top).
void seam_steps(const Image& image, double& inner, double& seam) {
  inner = seam = 0.0;
  const int w = image.width(), h = image.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double here = image.at(x, y);
      const double right = image.at((x + 1) % w, y), down = image.at(x, (y + 1) % h);
      const double step = std::max(std::abs(right - here), std::abs(down - here));
      if (x + 1 == w || y + 1 == h) {
        seam = std::max(seam, x + 1 == w ? std::abs(right - here) : std::abs(down - here));
      } else {
        inner = std::max(inner, step);
      }
    }
}

}  // namespace

TEST(TileNoiseImages, TileSeamlesslyAndAreDeterministic) {
  const int previous = thread_count();
  set_thread_count(1);
  const Image perlin1 = tile_perlin_image(64, 48, 4, 3, 3, 0.5, 6);
  const Image worley1 = tile_worley_image(64, 48, 8, 6, WorleyFeature::f1, 6);
  set_thread_count(2);
  const Image perlin2 = tile_perlin_image(64, 48, 4, 3, 3, 0.5, 6);
  const Image worley2 = tile_worley_image(64, 48, 8, 6, WorleyFeature::f1, 6);
  set_thread_count(previous);
  EXPECT_EQ(perlin1.data(), perlin2.data());
  EXPECT_EQ(worley1.data(), worley2.data());
  double inner = 0.0, seam = 0.0;
  seam_steps(perlin1, inner, seam);
  EXPECT_GT(inner, 0.0);
  EXPECT_LE(seam, 1.5 * inner);
  seam_steps(worley1, inner, seam);
  EXPECT_GT(inner, 0.0);
  EXPECT_LE(seam, 1.5 * inner);
  // The image is a sampling of the periodic function: the wrap neighbour equals the next sample.
  EXPECT_NEAR(worley1.at(0, 5), tile_worley_noise(Vec2((64 + 0.5) * 8 / 64, (5 + 0.5) * 6 / 48), 8, 6, 6).f1, 1e-6);
  const Image f2 = tile_worley_image(16, 16, 4, 4, WorleyFeature::f2, 6);
  const Image f1 = tile_worley_image(16, 16, 4, 4, WorleyFeature::f1, 6);
  const Image diff = tile_worley_image(16, 16, 4, 4, WorleyFeature::f2_minus_f1, 6);
  for (std::size_t i = 0; i < f1.data().size(); ++i) {
    EXPECT_LE(f1.data()[i], f2.data()[i]);
    EXPECT_NEAR(diff.data()[i], f2.data()[i] - f1.data()[i], 1e-6);
  }
  EXPECT_THROW(tile_perlin_image(8, 8, 0, 1, 1, 0.5, 1), InputError);
}
