#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "image/png_io.hpp"
#include "support/test_support.hpp"
#include "wound/abrasion.hpp"
#include "wound/bruise.hpp"
#include "wound_fixture.hpp"

using namespace forensim;

namespace {
// Maps are stored at 16 bits per channel (tiled_map_set.hpp): equal within half a 16-bit step.
void expect_same_colour(const Vec4f& a, const Vec4f& b, int x, int y) {
  for (int k = 0; k < 4; ++k) ASSERT_NEAR(a[k], b[k], 0.5f / 65535.0f + 1e-7f) << x << "," << y << " channel " << k;
}

std::vector<MapSet> all_phases(const WoundCanvas& c) {
  std::vector<MapSet> out;
  for (const char* p : {"vasoconstriction", "vasodilation", "scab_forming", "scab"}) {
    out.push_back(make_abrasion_key(p)->render(c, 0.0));
  }
  out.push_back(make_abrasion_key("maturation")->render(c, 0.3));
  return out;
}

// Golden comparison on 8-bit display values: mean difference < 1.5 codes, <= 1% of texels off by > 24.
void expect_matches_golden(const Image& picture, const std::string& name) {
  const std::filesystem::path path = test::tests_dir() / "golden/wound" / (name + ".png");
  const char* update = std::getenv("FORENSIM_UPDATE_GOLDEN");
  Image display = picture;
  display.set_encoding(PixelEncoding::data);
  if (update && std::string(update) == "1") {
    write_png(path, display);
    GTEST_SKIP() << "updated " << path;
  }
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing: run with FORENSIM_UPDATE_GOLDEN=1";
  const Image golden = read_png(path, PngTransfer::identity);
  ASSERT_EQ(golden.width(), picture.width());
  ASSERT_EQ(golden.height(), picture.height());
  ASSERT_EQ(golden.channels(), picture.channels());
  double total = 0;
  int differing = 0;
  for (int y = 0; y < picture.height(); ++y)
    for (int x = 0; x < picture.width(); ++x) {
      double worst = 0;
      for (int c = 0; c < picture.channels(); ++c) {
        const double v = std::clamp(static_cast<double>(picture.at(x, y, c)), 0.0, 1.0);
        const double d = std::abs(std::round(v * 255.0) - golden.at(x, y, c) * 255.0);
        total += d;
        worst = std::max(worst, d);
      }
      if (worst > 24) ++differing;
    }
  const double pixels = static_cast<double>(picture.width()) * picture.height();
  EXPECT_LT(total / (pixels * picture.channels()), 1.5) << name;
  EXPECT_LE(differing, 0.01 * pixels) << name;
}
}  // namespace

TEST(Abrasion, PhasesAreDeterministicForASeedAndThreadCount) {
  const auto canvas = test::fixture_canvas(96);
  set_thread_count(1);
  const auto one = all_phases(*canvas);
  set_thread_count(2);
  const auto two = all_phases(*canvas);
  set_thread_count(0);
  const auto again = all_phases(*test::fixture_canvas(96));
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].color.data(), two[i].color.data()) << i;
    EXPECT_EQ(one[i].reflection.data(), two[i].reflection.data()) << i;
    EXPECT_EQ(one[i].height_mm.data(), two[i].height_mm.data()) << i;
    EXPECT_EQ(one[i].color.data(), again[i].color.data()) << i;
  }
  const auto other_seed =
      make_abrasion_key("scab")->render(*test::fixture_canvas(96, DistanceMode::surface, ShapeMode::strokes, 8), 0.0);
  EXPECT_NE(other_seed.height_mm.data(), one[3].height_mm.data());
}

TEST(Abrasion, PhasesFollowTheThesis) {
  const auto canvas = test::fixture_canvas(128);
  const WoundCanvas& c = *canvas;
  const auto maps = all_phases(c);
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      const bool in = c.shape.at(x, y) >= 0.5f;
      // Vasoconstriction: lower skin inside, upper outside (4.3.1).
      expect_same_colour(maps[0].color.rgba(x, y), in ? c.lower_skin.rgba(x, y) : c.upper_skin.rgba(x, y), x, y);
      // Only the scab has relief, only inside the wound, at most scab_height_mm.
      ASSERT_EQ(maps[1].height_mm.at(x, y), 0.0f);
      ASSERT_GE(maps[3].height_mm.at(x, y), 0.0f);
      ASSERT_LE(maps[3].height_mm.at(x, y), 0.8f + 1e-6f);
      if (!in) {
        ASSERT_EQ(maps[3].height_mm.at(x, y), 0.0f);
        // Glow: red at the border fading to the upper skin at 12.5 mm (4.3.2).
        const float d = c.outside_mm.at(x, y);
        if (d > 12.5f) {
          expect_same_colour(maps[1].color.rgba(x, y), c.upper_skin.rgba(x, y), x, y);
        }
      }
    }
  // Glow is monotone: redder (relative to skin) nearer the wound.
  double near_red = 0, far_red = 0;
  int nn = 0, nf = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      const float d = c.outside_mm.at(x, y);
      if (c.shape.at(x, y) >= 0.5f || !std::isfinite(d)) continue;
      const double r = maps[2].color.at(x, y, 0) - maps[2].color.at(x, y, 1);
      if (d < 2.0f) near_red += r, ++nn;
      if (d > 8.0f && d < 12.0f) far_red += r, ++nf;
    }
  ASSERT_GT(nn, 0);
  ASSERT_GT(nf, 0);
  EXPECT_GT(near_red / nn, far_red / nf + 0.1);
}

TEST(Abrasion, MaturationAreaFallsToZeroAtTheEnd) {
  const auto canvas = test::fixture_canvas(128);
  const MaturationKey key;
  std::size_t previous = canvas->wound_texels + 1;
  for (double p : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const std::size_t area = visible_wound_texels(*canvas, key.render(*canvas, p));
    EXPECT_LE(area, previous) << p;
    previous = area;
    if (p == 0.0) {
      EXPECT_GT(area, canvas->wound_texels / 2);
    }
  }
  EXPECT_EQ(previous, 0u);
  const auto [outer, inner] = key.borders_mm(*canvas, 0.0);
  EXPECT_EQ(outer, 0.0);
  EXPECT_GT(inner, 0.0);
}

TEST(Abrasion, GoldenImagesOfEachPhase) {
  const auto canvas = test::fixture_canvas(128);
  const auto maps = all_phases(*canvas);
  const char* names[] = {"vasoconstriction", "vasodilation", "scab_forming", "scab", "maturation"};
  for (std::size_t i = 0; i < maps.size(); ++i) expect_matches_golden(maps[i].color.with_channels(3), names[i]);
  expect_matches_golden(maps[3].height_mm, "scab_height");
}

TEST(Bruise, ColourFollowsHaemoglobinDegradation) {
  const auto canvas = test::fixture_canvas(64);
  Timeline t(default_bruise_timeline());
  t.render(canvas);
  // At the wound's deepest texel: blue dominates red early, green then yellow later, skin at the end.
  int bx = 0, by = 0;
  float best = -1;
  for (int y = 0; y < canvas->height(); ++y)
    for (int x = 0; x < canvas->width(); ++x)
      if (canvas->inside_mm.at(x, y) > best) best = canvas->inside_mm.at(x, y), bx = x, by = y;
  auto ratio = [&](double time, int a, int b) {
    MapSet m;
    t.sample(time, m);
    const Vec4f v = m.color.rgba(bx, by), s = canvas->upper_skin.rgba(bx, by);
    return (v[a] / s[a]) / (v[b] / s[b]);
  };
  EXPECT_GT(ratio(86400.0, 2, 0), 1.05);      // day 1: blue over red (relative to the skin)
  EXPECT_GT(ratio(5 * 86400.0, 1, 0), 1.05);  // day 5: green over red
  EXPECT_GT(ratio(8 * 86400.0, 0, 2), 1.05);  // day 8: yellow: red and green over blue
  MapSet end;
  t.sample(30 * 86400.0, end);
  EXPECT_NEAR(end.color.rgba(bx, by).x(), canvas->upper_skin.rgba(bx, by).x(), 0.05);
}
