#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/distance_transform.hpp"

using namespace forensim;

namespace {

std::vector<std::uint8_t> random_mask(int w, int h, double density, std::uint64_t seed) {
  RandomStream rng(seed, 0);
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(w * h));
  for (auto& m : mask) m = rng.uniform() < density ? 1 : 0;
  return mask;
}

std::vector<double> brute_force(const std::vector<std::uint8_t>& mask, int w, int h) {
  std::vector<double> out(mask.size(), std::numeric_limits<double>::infinity());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int v = 0; v < h; ++v)
        for (int u = 0; u < w; ++u)
          if (mask[static_cast<std::size_t>(v * w + u)]) {
            const double d = double(x - u) * (x - u) + double(y - v) * (y - v);
            double& o = out[static_cast<std::size_t>(y * w + x)];
            if (d < o) o = d;
          }
  return out;
}

}  // namespace

TEST(DistanceTransform, EqualsBruteForceExactlyOnRandomMasks) {
  int trial = 0;
  for (double density : {0.005, 0.05, 0.3, 0.9}) {
    for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 9}, std::pair{13, 1}, std::pair{17, 11}, std::pair{32, 29}}) {
      const std::vector<std::uint8_t> mask = random_mask(w, h, density, static_cast<std::uint64_t>(++trial));
      const std::vector<double> fast = squared_distance_transform(mask, w, h);
      const std::vector<double> slow = brute_force(mask, w, h);
      ASSERT_EQ(fast, slow) << w << "x" << h << " density " << density;
    }
  }
}

TEST(DistanceTransform, OneDimensionalLowerEnvelope) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> f{inf, 3.0, inf, inf, 0.0, inf, 10.0, inf};
  const std::vector<double> d = squared_distance_transform_1d(f);
  for (int q = 0; q < 8; ++q) {
    double expected = inf;
    for (int p = 0; p < 8; ++p) expected = std::min(expected, double(q - p) * (q - p) + f[static_cast<std::size_t>(p)]);
    EXPECT_EQ(d[static_cast<std::size_t>(q)], expected);
  }
  EXPECT_TRUE(squared_distance_transform_1d({}).empty());
  EXPECT_EQ(squared_distance_transform_1d({inf, inf})[1], inf);
}

TEST(DistanceTransform, SignedAndUnsignedImagesAndThreads) {
  const int w = 40, h = 30;
  Image mask(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) mask.at(x, y) = (x >= 10 && x < 30 && y >= 5 && y < 25) ? 1.0f : 0.0f;
  const int previous = thread_count();
  set_thread_count(1);
  const Image s1 = signed_distance(mask);
  set_thread_count(2);
  const Image s2 = signed_distance(mask);
  set_thread_count(previous);
  EXPECT_EQ(s1.data(), s2.data());
  // Analytic values for an axis-aligned square.
  EXPECT_FLOAT_EQ(s1.at(5, 15), 5.0f);                                       // 5 texels left of the square
  EXPECT_FLOAT_EQ(s1.at(5, 0), static_cast<float>(std::sqrt(25.0 + 25.0)));  // diagonal to the corner
  EXPECT_FLOAT_EQ(s1.at(12, 15), -3.0f);                                     // nearest outside texel is x = 9
  EXPECT_FLOAT_EQ(s1.at(10, 5), -1.0f);
  const Image unsigned_distance = distance_to_mask(mask);
  EXPECT_FLOAT_EQ(unsigned_distance.at(12, 15), 0.0f);
  EXPECT_FLOAT_EQ(unsigned_distance.at(35, 15), 6.0f);
  // Empty mask: infinite distances; full mask: infinite negative distances.
  const Image empty = distance_to_mask(Image(4, 3, 1, 0.0f));
  for (float v : empty.data()) EXPECT_TRUE(std::isinf(v));
  const Image full = signed_distance(Image(4, 3, 1, 1.0f));
  for (float v : full.data()) EXPECT_TRUE(std::isinf(v) && v < 0);
  EXPECT_THROW(squared_distance_transform(std::vector<std::uint8_t>(5), 2, 2), InputError);
}

TEST(DistanceTransform, ParallelLargeMaskMatchesSerial) {
  const int w = 300, h = 257;
  const std::vector<std::uint8_t> mask = random_mask(w, h, 0.001, 99);
  const int previous = thread_count();
  set_thread_count(1);
  const std::vector<double> a = squared_distance_transform(mask, w, h);
  set_thread_count(2);
  const std::vector<double> b = squared_distance_transform(mask, w, h);
  set_thread_count(previous);
  EXPECT_EQ(a, b);
  // Spot-check against brute force at a few texels.
  RandomStream rng(1, 1);
  for (int i = 0; i < 20; ++i) {
    const int x = static_cast<int>(rng.uniform_int(0, w - 1)), y = static_cast<int>(rng.uniform_int(0, h - 1));
    double best = std::numeric_limits<double>::infinity();
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u)
        if (mask[static_cast<std::size_t>(v * w + u)])
          best = std::min(best, double(x - u) * (x - u) + double(y - v) * (y - v));
    EXPECT_EQ(a[static_cast<std::size_t>(y * w + x)], best);
  }
}
