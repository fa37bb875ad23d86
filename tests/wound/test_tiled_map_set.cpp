#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <set>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "wound/abrasion.hpp"
#include "wound/tiled_map_set.hpp"
#include "wound/timeline.hpp"
#include "wound_fixture.hpp"

using namespace forensim;

namespace {
// A 150 x 70 set (3 x 2 tiles, partial at the edges): tile 0 skin, the others own random maps.
TiledMapSet random_set(std::uint64_t seed, float skin_reflection) {
  TiledMapSet s;
  s.reset(150, 70, skin_reflection);
  RandomStream rng(seed, 0);
  for (int t = 1; t < s.tile_count(); ++t) {
    std::uint16_t* c = s.own_color(t);
    for (std::size_t i = 0; i < 4 * tiled_map_tile_texels; ++i) c[i] = to_unorm16(static_cast<float>(rng.uniform()));
    if (t % 2 == 0) {
      std::uint16_t* r = s.own_reflection(t);
      float* h = s.own_height(t);
      for (std::size_t i = 0; i < tiled_map_tile_texels; ++i) {
        r[i] = to_unorm16(static_cast<float>(rng.uniform()));
        h[i] = static_cast<float>(rng.uniform(-1.0, 1.0));
      }
    }
  }
  return s;
}

Image random_skin(int w, int h) {
  Image skin(w, h, 4, 1.0f);
  RandomStream rng(3, 1);
  for (float& v : skin.data()) v = static_cast<float>(rng.uniform());
  return skin;
}
}  // namespace

TEST(TiledMapSet, BlendEqualsThePlainBlendAndTouchesOnlyDifferingTiles) {
  const Image skin = random_skin(150, 70);
  TiledMapSet a = random_set(1, 0.25f), b = random_set(2, 0.25f);
  b.share_tile(5, a.tile(5));  // a tile both share
  b.share_tile(3, MapTile{});  // skin in b, own in a
  TiledMapSet out;
  lerp_tiled_map_sets(a, b, 0.3f, skin, out);
  // Skin in both stays skin; shared stays shared (no copy).
  EXPECT_FALSE(out.tile(0).color);
  EXPECT_FALSE(out.tile(0).reflection);
  EXPECT_EQ(out.tile(5).color, a.tile(5).color);
  EXPECT_NE(out.tile(3).color, a.tile(3).color);
  MapSet expected = make_map_set(150, 70);
  lerp_map_sets(a.to_map_set(skin), b.to_map_set(skin), 0.3f, expected);
  const MapSet got = out.to_map_set(skin);
  for (std::size_t i = 0; i < got.color.data().size(); ++i)
    ASSERT_NEAR(got.color.data()[i], expected.color.data()[i], 0.5f / 65535.0f + 1e-6f) << i;
  for (std::size_t i = 0; i < got.reflection.data().size(); ++i) {
    ASSERT_NEAR(got.reflection.data()[i], expected.reflection.data()[i], 0.5f / 65535.0f + 1e-6f) << i;
    ASSERT_NEAR(got.height_mm.data()[i], expected.height_mm.data()[i], 1e-6f) << i;
  }
  // Skin texels of the set read the skin exactly.
  EXPECT_EQ(got.color.rgba(3, 4), skin.rgba(3, 4));
  EXPECT_FLOAT_EQ(got.reflection.at(3, 4), 0.25f);
  EXPECT_THROW(lerp_tiled_map_sets(a, b, 0.5f, skin, a), InputError);
  TiledMapSet small;
  small.reset(10, 10, 0.25f);
  EXPECT_THROW(lerp_tiled_map_sets(a, small, 0.5f, skin, out), InputError);
}

TEST(TiledMapSet, RenderingAgainReusesTheBuffersItAloneHolds) {
  TiledMapSet s = random_set(4, 0.1f);
  std::set<const std::uint16_t*> before;
  for (int t = 1; t < s.tile_count(); ++t) before.insert(s.tile(t).color->data());
  s.reset(150, 70, 0.1f);
  EXPECT_EQ(s.stored_texels(), 0u);
  // Writing the same tiles again takes the buffers back (no allocation).
  std::set<const std::uint16_t*> again;
  for (int t = 1; t < s.tile_count(); ++t) again.insert(s.own_color(t));
  EXPECT_EQ(again, before);
  // A buffer shared with another set is never written through: the writer gets another one.
  TiledMapSet other;
  other.share(s);
  const std::uint16_t* shared = other.tile(1).color->data();
  EXPECT_NE(s.own_color(1), shared);
  EXPECT_EQ(other.tile(1).color->data(), shared);
  EXPECT_NE(s.tile(1).color, other.tile(1).color);
}

TEST(TiledMapSet, TimelineSamplesStoreOnlyWhatTheirKeysChangeAtAnyThreadCount) {
  const auto canvas = test::fixture_canvas(256);
  Timeline t(default_abrasion_timeline());
  t.render(canvas);
  const TiledMapSet& vc = t.entry_tiles(1);
  const TiledMapSet& vd = t.entry_tiles(2);
  // Some tiles of this region are beyond the glow: the keys leave them to the skin.
  std::size_t skin_tiles = 0;
  for (int i = 0; i < vd.tile_count(); ++i) skin_tiles += vd.tile(i).color ? 0 : 1;
  EXPECT_GT(skin_tiles, 0u);
  set_thread_count(1);
  TiledMapSet one;
  t.sample(600.0, one);
  set_thread_count(2);
  TiledMapSet two;
  t.sample(600.0, two);
  set_thread_count(0);
  for (int i = 0; i < one.tile_count(); ++i) {
    const bool changed = vc.tile(i).color || vd.tile(i).color;
    EXPECT_EQ(static_cast<bool>(one.tile(i).color), changed) << i;
    if (changed) {
      EXPECT_EQ(*one.tile(i).color, *two.tile(i).color) << i;
    }
  }
  // In a hold the sample shares the key's tiles.
  TiledMapSet hold;
  t.sample(86400.0, hold);  // scab-forming, held from 2 h to 2 d
  const TiledMapSet& held = t.entry_tiles(3);
  for (int i = 0; i < hold.tile_count(); ++i) EXPECT_EQ(hold.tile(i).color, held.tile(i).color) << i;
}

TEST(TiledMapSet, SixteenBitCodesRoundTripAndClamp) {
  const float values[] = {-0.5f, 0.0f,      1e-6f,     0.25f,           0.5f, 0.7071f, 1.0f,
                          3.0f,  0.999999f, 0.123456f, 0.5f / 65535.0f, 0.9f};
  for (std::size_t i = 0; i + 4 <= std::size(values); ++i) {
    std::uint16_t four[4];
    to_unorm16x4(values + i, four);
    for (std::size_t k = 0; k < 4; ++k) {
      const float v = values[i + k];
      EXPECT_EQ(four[k], to_unorm16(v)) << v;
      EXPECT_NEAR(from_unorm16(four[k]), std::clamp(v, 0.0f, 1.0f), 0.5f / 65535.0f + 1e-7f) << v;
    }
  }
  EXPECT_EQ(to_unorm16(1.0f), 65535);
  EXPECT_EQ(to_unorm16(-1.0f), 0);
}
