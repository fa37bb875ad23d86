#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "texture/normal_from_height.hpp"
#include "wound/duration.hpp"
#include "wound/map_set.hpp"

using namespace forensim;

namespace {
MapSet ramp(int w, int h, float k) {
  MapSet m = make_map_set(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      m.color.set_rgba(x, y, Vec4f(k * x, k * y, 0.5f * k, 1.0f));
      m.reflection.at(x, y) = k * (x + y);
      m.height_mm.at(x, y) = -k * x;
    }
  return m;
}
}  // namespace

TEST(MapSet, LerpMidwayIsTheAverageAndRectLimitsIt) {
  const MapSet a = ramp(17, 9, 0.01f), b = ramp(17, 9, 0.05f);
  MapSet out = make_map_set(17, 9, Vec4f(9, 9, 9, 9), 9.0f);
  lerp_map_sets(a, b, 0.5f, out, TexelRect{3, 2, 11, 7});
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 17; ++x) {
      const bool in = x >= 3 && x < 11 && y >= 2 && y < 7;
      for (int c = 0; c < 4; ++c) {
        const float expect = in ? 0.5f * (a.color.at(x, y, c) + b.color.at(x, y, c)) : 9.0f;
        EXPECT_NEAR(out.color.at(x, y, c), expect, 1e-6f);
      }
      EXPECT_NEAR(out.height_mm.at(x, y), in ? 0.5f * (a.height_mm.at(x, y) + b.height_mm.at(x, y)) : 0.0f, 1e-6f);
    }
  MapSet full = make_map_set(17, 9);
  lerp_map_sets(a, b, 0.0f, full);
  EXPECT_EQ(full.color.data(), a.color.data());
  MapSet wrong = make_map_set(5, 5);
  EXPECT_THROW(lerp_map_sets(a, b, 0.5f, wrong), InputError);
}

TEST(MapSet, NormalFromHeightMatchesAnalyticSlope) {
  Image h(16, 8, 1, 0.0f, PixelEncoding::data);
  // h = 0.5 mm per mm along u at 4 texels per mm -> 0.125 mm per texel.
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) h.at(x, y) = 0.125f * x;
  const Image n = normal_from_height(h, 4.0);
  const double inv = 1.0 / std::sqrt(1.0 + 0.25);
  EXPECT_NEAR(n.at(5, 3, 0), -0.5 * inv * 0.5 + 0.5, 1e-5);
  EXPECT_NEAR(n.at(5, 3, 1), 0.5, 1e-6);
  EXPECT_NEAR(n.at(5, 3, 2), inv * 0.5 + 0.5, 1e-5);
  EXPECT_THROW(normal_from_height(h, 0.0), InputError);
}

TEST(Duration, ParsesRealUnits) {
  EXPECT_DOUBLE_EQ(parse_duration("36h"), 36 * 3600.0);
  EXPECT_DOUBLE_EQ(parse_duration("3d"), 3 * 86400.0);
  EXPECT_DOUBLE_EQ(parse_duration("2w"), 14 * 86400.0);
  EXPECT_DOUBLE_EQ(parse_duration("10min"), 600.0);
  EXPECT_DOUBLE_EQ(parse_duration("1.5"), 1.5);
  EXPECT_THROW(parse_duration("3 days"), InputError);
  EXPECT_THROW(parse_duration("-1h"), InputError);
  EXPECT_THROW(parse_duration("h"), InputError);
  const auto list = parse_durations("1h,36h,5d");
  ASSERT_EQ(list.size(), 3u);
  EXPECT_DOUBLE_EQ(list[2], 5 * 86400.0);
  EXPECT_EQ(format_injury_time(36 * 3600.0), "1.5d");
}
