#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/convex_hull.hpp"
#include "texture/gradient_edge.hpp"
#include "texture/image_ops.hpp"
#include "texture/polygon_fill.hpp"

using namespace forensim;

namespace {

// Reference distance from a point to a segment by projection clamped to [0, 1].
double reference_segment_distance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

const Vec4f red(0.79f, 0.0f, 0.0f, 1.0f), skin(0.9f, 0.7f, 0.6f, 1.0f), black(0.0f, 0.0f, 0.0f, 1.0f);

}  // namespace

TEST(GradientEdge, SegmentDistanceAlgorithm33MatchesProjection) {
  RandomStream rng(4, 0);
  for (int i = 0; i < 2000; ++i) {
    const Vec2 a(rng.uniform(-5, 5), rng.uniform(-5, 5)), b(rng.uniform(-5, 5), rng.uniform(-5, 5));
    const Vec2 p(rng.uniform(-8, 8), rng.uniform(-8, 8));
    ASSERT_NEAR(point_segment_distance(a, b, p), reference_segment_distance(a, b, p), 1e-9);
  }
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(1, 1), Vec2(1, 1), Vec2(4, 5)), 5.0);
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(0, 0), Vec2(10, 0), Vec2(3, -2)), 2.0);
  EXPECT_TRUE(std::isinf(polygon_edge_distance({}, Vec2(0, 0))));
}

TEST(GradientEdge, MaskFormEqualsBruteForceOnRandomMasks) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const int w = 19 + static_cast<int>(seed), h = 14;
    Image shape(w, h, 1);
    RandomStream rng(seed, 3);
    for (float& v : shape.data()) v = rng.uniform() < 0.4 ? 1.0f : 0.0f;
    for (GradientSide side : {GradientSide::inside, GradientSide::outside}) {
      const double thickness = 3.5;
      const Image out = draw_gradient_edge(shape, thickness, side, red, skin);
      const Image distance = edge_distance(shape, side);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const bool inside = shape.at(x, y) >= 0.5f;
          const bool rendered = side == GradientSide::inside ? inside : !inside;
          double d = std::numeric_limits<double>::infinity();
          for (int v = 0; v < h; ++v)
            for (int u = 0; u < w; ++u)
              if ((shape.at(u, v) >= 0.5f) != inside) d = std::min(d, std::hypot(double(x - u), double(y - v)));
          if (!rendered) {
            ASSERT_TRUE(std::isinf(distance.at(x, y)));
            ASSERT_EQ(out.rgba(x, y), black);
            continue;
          }
          ASSERT_FLOAT_EQ(distance.at(x, y), static_cast<float>(d));
          const Vec4f expected = d <= thickness ? blend_lerp(red, skin, static_cast<float>(d / thickness)) : black;
          for (int c = 0; c < 4; ++c) ASSERT_NEAR(out.rgba(x, y)[c], expected[c], 1e-6f);
        }
    }
  }
}

TEST(GradientEdge, HullFormFollowsAlgorithm34) {
  const int w = 48, h = 40;
  const std::vector<Vec2> hull = convex_hull({{10.2, 8.1}, {36.7, 10.4}, {30.3, 31.6}, {12.9, 28.2}, {20, 20}});
  Image shape(w, h, 1, 0.0f);
  fill_hull(shape, hull);
  const double thickness = 6.0;
  const Image glow = draw_gradient_edge_hull(hull, shape, thickness, GradientSide::outside, red, skin);
  const Image rim = draw_gradient_edge_hull(hull, shape, thickness, GradientSide::inside, red, black);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec2 centre(x + 0.5, y + 0.5);
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < hull.size(); ++i)
        d = std::min(d, reference_segment_distance(hull[i], hull[(i + 1) % hull.size()], centre));
      const bool inside = shape.at(x, y) >= 0.5f;
      const Vec4f expected_glow = inside || d > thickness ? black : blend_lerp(red, skin, float(d / thickness));
      const Vec4f expected_rim = !inside || d > thickness ? black : blend_lerp(red, black, float(d / thickness));
      for (int c = 0; c < 4; ++c) {
        ASSERT_NEAR(glow.rgba(x, y)[c], expected_glow[c], 1e-5f);
        ASSERT_NEAR(rim.rgba(x, y)[c], expected_rim[c], 1e-5f);
      }
    }
  // The mask form measures to texel centres: never nearer than the hull, at most a texel diagonal farther.
  const Image distance = edge_distance(shape, GradientSide::outside);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (shape.at(x, y) >= 0.5f) continue;
      const double hull_distance = polygon_edge_distance(hull, Vec2(x + 0.5, y + 0.5));
      EXPECT_GE(distance.at(x, y), hull_distance - 1e-5);
      EXPECT_LE(distance.at(x, y), hull_distance + std::sqrt(2.0) + 1e-5);
    }
  }
  EXPECT_THROW(draw_gradient_edge(shape, 0.0, GradientSide::inside, red, skin), InputError);
}

TEST(GradientEdge, DeterministicAtAnyThreadCount) {
  Image shape(120, 90, 1, 0.0f);
  fill_hull(shape, convex_hull({{20, 10}, {100, 25}, {80, 80}, {15, 60}}));
  const int previous = thread_count();
  set_thread_count(1);
  const Image a = draw_gradient_edge(shape, 25.0, GradientSide::outside, red, skin);
  set_thread_count(2);
  const Image b = draw_gradient_edge(shape, 25.0, GradientSide::outside, red, skin);
  set_thread_count(previous);
  EXPECT_EQ(a.data(), b.data());
}
