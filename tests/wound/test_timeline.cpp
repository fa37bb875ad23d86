#include <gtest/gtest.h>

#include "core/error.hpp"
#include "wound/abrasion.hpp"
#include "wound/timeline.hpp"
#include "wound_fixture.hpp"

using namespace forensim;

namespace {
void expect_same(const MapSet& a, const MapSet& b) {
  EXPECT_EQ(a.color.data(), b.color.data());
  EXPECT_EQ(a.reflection.data(), b.reflection.data());
  EXPECT_EQ(a.height_mm.data(), b.height_mm.data());
}

Timeline rendered_default(std::shared_ptr<WoundCanvas> canvas) {
  Timeline t(default_abrasion_timeline());
  t.render(canvas);
  return t;
}
}  // namespace

TEST(Timeline, EndsAndHoldsReproduceTheirKeyMapsExactly) {
  const auto canvas = test::fixture_canvas(64);
  const Timeline t = rendered_default(canvas);
  const auto& e = t.entries();
  MapSet out;
  t.sample(-5.0, out);
  expect_same(out, t.entry_maps(0));
  t.sample(1e9, out);
  expect_same(out, t.entry_maps(e.size() - 1));
  // Hold pairs: anywhere between two entries of the same key and position gives that key's maps.
  for (std::size_t i = 0; i + 1 < e.size(); ++i) {
    if (e[i].key != e[i + 1].key || e[i].local_position != e[i + 1].local_position) continue;
    for (double w : {0.0, 0.3, 0.77}) {
      t.sample(e[i].time_s + w * (e[i + 1].time_s - e[i].time_s), out);
      expect_same(out, t.entry_maps(i));
    }
  }
  // Every entry's time gives its maps (the later one of an instant cut).
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (i + 1 < e.size() && e[i + 1].time_s == e[i].time_s) continue;
    t.sample(e[i].time_s, out);
    expect_same(out, t.entry_maps(i));
  }
}

TEST(Timeline, MidwayBetweenKeysIsTheAverageAndFullSamplesMatch) {
  const auto canvas = test::fixture_canvas(64);
  const Timeline t = rendered_default(canvas);
  // Vasoconstriction (held to 5 min) -> vasodilation at 15 min: midway at 10 min.
  MapSet out;
  t.sample(600.0, out);
  const MapSet& a = t.entry_maps(1);
  const MapSet& b = t.entry_maps(2);
  ASSERT_NE(a.color.data(), b.color.data());
  for (std::size_t i = 0; i < out.color.data().size(); ++i) {
    // The blend is stored at 16 bits (tiled_map_set.hpp): within half a 16-bit step of the average.
    ASSERT_NEAR(out.color.data()[i], 0.5f * (a.color.data()[i] + b.color.data()[i]), 0.5f / 65535.0f + 1e-7f);
  }
  MapSet full = skin_map_set(Image(canvas->full_width, canvas->full_height, 4, 0.3f), 0.25f);
  for (double time : {600.0, 3 * 86400.0, 20 * 86400.0}) {
    t.sample(time, out);
    t.sample_full(time, full);
    for (int y = 0; y < out.height(); ++y)
      for (int x = 0; x < out.width(); ++x)
        ASSERT_EQ(out.color.rgba(x, y), full.color.rgba(x + canvas->region.x0, y + canvas->region.y0));
  }
  EXPECT_FLOAT_EQ(full.color.at(0, 0, 0), 0.3f);  // outside the region: untouched skin
}

TEST(Timeline, InstantCutJumpsAndMaturationReRenders) {
  const auto canvas = test::fixture_canvas(64);
  const Timeline t = rendered_default(canvas);
  const double cut = 10 * 86400.0;
  MapSet before, at;
  t.sample(cut - 1.0, before);
  t.sample(cut, at);
  const auto& e = t.entries();
  std::size_t scab = 0, maturation = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (e[i].key->name() == "scab") scab = i;
    if (e[i].key->name() == "maturation" && maturation == 0) maturation = i;
  }
  expect_same(before, t.entry_maps(scab));
  expect_same(at, t.entry_maps(maturation));
  // Between the maturation entries the key is rendered at the interpolated position.
  MapSet mid;
  t.sample(19 * 86400.0, mid);
  const MapSet direct = e[maturation].key->render(*canvas, 0.5);
  expect_same(mid, direct);
}

TEST(Timeline, RejectsBadEntries) {
  const auto key = make_abrasion_key("scab");
  EXPECT_THROW(Timeline({{0.0, key, 0.0, "a"}}), InputError);
  EXPECT_THROW(Timeline({{10.0, key, 0.0, "a"}, {5.0, key, 0.0, "b"}}), InputError);
  EXPECT_THROW(Timeline({{0.0, key, 0.0, "a"}, {0.0, key, 0.0, "b"}, {0.0, key, 0.0, "c"}}), InputError);
  EXPECT_THROW(Timeline({{0.0, nullptr, 0.0, "a"}, {1.0, key, 0.0, "b"}}), InputError);
  EXPECT_THROW(make_abrasion_key("scabby"), InputError);
}
