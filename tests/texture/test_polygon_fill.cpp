#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/convex_hull.hpp"
#include "texture/polygon_fill.hpp"

using namespace forensim;

namespace {

// Brute-force crossing count and winding number of a ray from p towards +x (half-open in y).
void ray_counts(const std::vector<std::vector<Vec2>>& rings, const Vec2& p, int& crossings, int& winding) {
  crossings = winding = 0;
  for (const auto& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 &a = ring[i], &b = ring[(i + 1) % ring.size()];
      if (a[1] == b[1]) continue;
      const bool down = a[1] < b[1];
      const double lo = std::min(a[1], b[1]), hi = std::max(a[1], b[1]);
      if (!(p[1] >= lo && p[1] < hi)) continue;
      const double x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
      if (x > p[0]) {
        ++crossings;
        winding += down ? 1 : -1;
      }
    }
}

std::vector<Vec2> random_polygon(RandomStream& rng, int n, double cx, double cy, double r) {
  std::vector<Vec2> ring;
  for (int i = 0; i < n; ++i)  // star-shaped around the centre: simple
    ring.emplace_back(cx + r * rng.uniform(0.3, 1.0) * std::cos(6.283185307179586 * (i + rng.uniform(0, 0.9)) / n),
                      cy + r * rng.uniform(0.3, 1.0) * std::sin(6.283185307179586 * (i + rng.uniform(0, 0.9)) / n));
  return ring;
}

}  // namespace

TEST(PolygonFill, ScanlineEqualsPointInPolygonBruteForce) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    RandomStream rng(seed, 0);
    std::vector<std::vector<Vec2>> rings{random_polygon(rng, 12, 20.3, 18.7, 16.0),
                                         random_polygon(rng, 7, 24.1, 20.2, 6.0)};  // overlapping or a hole
    if (seed % 4 == 0) {  // a self-intersecting random ring as well
      std::vector<Vec2> scribble;
      for (int i = 0; i < 9; ++i) scribble.emplace_back(rng.uniform(-3, 43), rng.uniform(-3, 40));
      rings.push_back(scribble);
    }
    for (FillRule rule : {FillRule::even_odd, FillRule::non_zero}) {
      const Image filled = fill_polygon(40, 37, rings, rule);
      for (int y = 0; y < 37; ++y)
        for (int x = 0; x < 40; ++x) {
          int crossings = 0, winding = 0;
          ray_counts(rings, Vec2(x + 0.5, y + 0.5), crossings, winding);
          const bool inside = rule == FillRule::even_odd ? crossings % 2 == 1 : winding != 0;
          ASSERT_EQ(filled.at(x, y), inside ? 1.0f : 0.0f) << "seed " << seed << " at " << x << "," << y;
        }
    }
  }
}

TEST(PolygonFill, PentagramRulesDiffer) {
  std::vector<Vec2> star;
  for (int i = 0; i < 5; ++i) {
    const double a = 6.283185307179586 * (2 * i) / 5 + 0.1;
    star.emplace_back(32 + 28 * std::cos(a), 32 + 28 * std::sin(a));
  }
  const Image even_odd = fill_polygon(64, 64, {star}, FillRule::even_odd);
  const Image non_zero = fill_polygon(64, 64, {star}, FillRule::non_zero);
  EXPECT_EQ(even_odd.at(32, 32), 0.0f);  // the inner pentagon is wound twice
  EXPECT_EQ(non_zero.at(32, 32), 1.0f);
}

TEST(PolygonFill, AntialiasedCoverageIntegratesToTheArea) {
  RandomStream rng(5, 0);
  const std::vector<Vec2> ring = random_polygon(rng, 15, 30.2, 25.9, 20.0);
  const Image coverage = fill_polygon(64, 56, {ring}, FillRule::non_zero, true, 64);
  double sum = 0.0;
  for (float v : coverage.data()) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
    sum += v;
  }
  EXPECT_NEAR(sum, std::abs(polygon_signed_area(ring)), 0.05);
  // An axis-aligned rectangle on half texels: exact fractional coverage.
  const Image rect =
      fill_polygon(8, 8, {{{1.5, 2.25}, {5.25, 2.25}, {5.25, 6.0}, {1.5, 6.0}}}, FillRule::even_odd, true, 4);
  EXPECT_FLOAT_EQ(rect.at(1, 3), 0.5f);
  EXPECT_FLOAT_EQ(rect.at(3, 2), 0.75f);
  EXPECT_FLOAT_EQ(rect.at(5, 2), 0.25f * 0.75f);
  EXPECT_FLOAT_EQ(rect.at(3, 4), 1.0f);
  EXPECT_FLOAT_EQ(rect.at(3, 6), 0.0f);
}

TEST(PolygonFill, HullFillAlgorithm42MatchesScanlineForBothOrientations) {
  RandomStream rng(9, 0);
  std::vector<Vec2> points;
  for (int i = 0; i < 40; ++i) points.emplace_back(rng.uniform(3.1, 60.2), rng.uniform(4.3, 50.7));
  const std::vector<Vec2> hull = convex_hull(points);
  std::vector<Vec2> reversed(hull.rbegin(), hull.rend());
  Image a(64, 56, 1, 0.5f), b(64, 56, 1, 0.5f);
  fill_hull(a, hull);
  fill_hull(b, reversed);
  const Image scan = fill_polygon(64, 56, {hull});
  int inside = 0;
  for (int y = 0; y < 56; ++y)
    for (int x = 0; x < 64; ++x) {
      ASSERT_EQ(a.at(x, y), b.at(x, y));
      const bool in_box = x + 0.5 >= 3.1 && x + 0.5 <= 60.2 && y + 0.5 >= 4.3 && y + 0.5 <= 50.7;
      if (a.at(x, y) == 0.5f) {
        // Untouched: outside the hull's bounding box.
        ASSERT_EQ(scan.at(x, y), 0.0f);
        continue;
      }
      ASSERT_TRUE(in_box || a.at(x, y) == 0.0f);
      ASSERT_EQ(a.at(x, y), scan.at(x, y)) << x << "," << y;
      inside += a.at(x, y) == 1.0f;
    }
  EXPECT_NEAR(inside, std::abs(polygon_signed_area(hull)), 0.1 * std::abs(polygon_signed_area(hull)));
  // Degenerate hulls fill nothing.
  Image c(4, 4, 1, 0.5f);
  fill_hull(c, {{1, 1}, {2, 2}});
  for (float v : c.data()) EXPECT_EQ(v, 0.5f);
}

TEST(PolygonFill, RejectsBadInputAndIsDeterministic) {
  EXPECT_THROW(fill_polygon(4, 4, {{{0, 0}, {1, std::nan("")}, {2, 0}}}), InputError);
  EXPECT_THROW(fill_polygon(4, 4, {{{0, 0}, {1e300, 1e300}, {-1e300, 2}}}), InputError);
  EXPECT_THROW(fill_polygon(4, 4, {{{0, 0}, {1, 1}, {2, 0}}}, FillRule::non_zero, true, 0), InputError);
  RandomStream rng(2, 0);
  const std::vector<Vec2> ring = random_polygon(rng, 30, 100, 80, 70);
  const int previous = thread_count();
  set_thread_count(1);
  const Image a = fill_polygon(200, 160, {ring}, FillRule::non_zero, true);
  set_thread_count(2);
  const Image b = fill_polygon(200, 160, {ring}, FillRule::non_zero, true);
  set_thread_count(previous);
  EXPECT_EQ(a.data(), b.data());
}
