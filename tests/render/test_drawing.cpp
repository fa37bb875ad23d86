#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "render/colour_bar.hpp"
#include "render/draw.hpp"
#include "render/render_settings.hpp"
#include "render/sheet.hpp"
#include "render/text.hpp"

using namespace forensim;

namespace {

int count_changed(const Image& a, const Image& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.data().size(); ++i) n += a.data()[i] != b.data()[i] ? 1 : 0;
  return n;
}

}  // namespace

TEST(Text, MeasuresAndDraws) {
  const TextMetrics short_text = measure_text("day 1", 20);
  const TextMetrics long_text = measure_text("day 1 after death", 20);
  EXPECT_GT(short_text.width, 20);
  EXPECT_GT(long_text.width, short_text.width);
  EXPECT_NEAR(measure_text("day 1", 40).width, 2 * short_text.width, 1.0);
  EXPECT_GT(short_text.ascent, 10);
  Image image(120, 40, 3, 1.0f, PixelEncoding::srgb);
  const Image blank = image;
  draw_text(image, 4, 4, "Tissue µm", 20, Vec4f(0, 0, 0, 1));
  const int changed = count_changed(image, blank);
  EXPECT_GT(changed, 60);
  // Everything drawn lies inside the text's box.
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 120; ++x)
      if (image.at(x, y, 0) != 1.0f) {
        EXPECT_LT(y, 4 + measure_text("T", 20).line_height() + 1);
        EXPECT_LT(x, 4 + measure_text("Tissue µm", 20).width + 2);
      }
  // Malformed UTF-8, far-off positions and empty strings are harmless.
  draw_text(image, 1e12, -5, "x", 20, Vec4f(0, 0, 0, 1));
  draw_text(image, 0, 0, std::string("\xff\xfe\xc3", 3), 12, Vec4f(0, 0, 0, 1));
  draw_text(image, 0, 0, "", 12, Vec4f(0, 0, 0, 1));
}

TEST(Drawing, LineCoversItsWidth) {
  Image image(50, 50, 4, 0.0f, PixelEncoding::srgb);
  draw_line(image, Vec2(5, 25), Vec2(45, 25), Vec4f(1, 0, 0, 1), 4.0);
  EXPECT_FLOAT_EQ(image.at(25, 24, 0), 1.0f);
  EXPECT_FLOAT_EQ(image.at(25, 25, 0), 1.0f);
  EXPECT_FLOAT_EQ(image.at(25, 20, 0), 0.0f);
  draw_disc(image, Vec2(10, 10), 3, Vec4f(0, 1, 0, 1));
  EXPECT_FLOAT_EQ(image.at(10, 10, 1), 1.0f);
  EXPECT_FLOAT_EQ(image.at(10, 16, 1), 0.0f);
  draw_line(image, Vec2(-1e9, 0), Vec2(1e9, 3), Vec4f(1, 1, 1, 1), 1.0);  // clipped, no hang
  const Image before = image;
  draw_line(image, Vec2(1e15, 0), Vec2(2e15, 3), Vec4f(1, 1, 1, 1), 1.0);
  draw_disc(image, Vec2(-1e300, 5), 3, Vec4f(1, 1, 1, 1));
  draw_disc(image, Vec2(std::nan(""), 5), 3, Vec4f(1, 1, 1, 1));
  EXPECT_TRUE(image.data() == before.data());
}

TEST(ColourBar, TicksAndLegendPanel) {
  EXPECT_EQ(format_tick(0.5, 0.1, -1), "0.5");
  EXPECT_EQ(format_tick(-0.0001, 0.25, -1), "0.00");
  EXPECT_EQ(format_tick(1.0 / 3.0, 1.0 / 3.0, -1), "0.333");
  EXPECT_EQ(format_tick(120, 50, -1), "120");
  ColourBar bar;
  bar.min = 0;
  bar.max = 10;
  bar.title = std::string("depth");
  bar.unit = std::string("mm");
  const Image picture(100, 200, 4, 0.5f, PixelEncoding::srgb);
  const Image legend = with_colour_bar(picture, bar);
  EXPECT_GT(legend.width(), 130);
  EXPECT_EQ(legend.height(), 200);
  // The bar's bottom shows the colormap's first colour, its top the last.
  bool found_low = false;
  const Vec3f low = bar.colormap.sample_srgb(0.0);
  for (int y = 150; y < 200 && !found_low; ++y)
    for (int x = 100; x < legend.width(); ++x)
      if ((legend.rgba(x, y).head<3>() - low).norm() < 0.05f) found_low = true;
  EXPECT_TRUE(found_low);
}

TEST(Sheet, GridSizeAndErrors) {
  std::vector<SheetCell> cells;
  for (int i = 0; i < 5; ++i) cells.push_back({Image(30, 20, 4, 1.0f, PixelEncoding::srgb), "c"});
  SheetStyle style;
  style.padding = 10;
  const Image sheet = make_sheet(cells, 3, "", style);
  EXPECT_EQ(sheet.width(), 3 * (30 + 10) + 10);
  EXPECT_GT(sheet.height(), 2 * (20 + 10));
  EXPECT_EQ(sheet.encoding(), PixelEncoding::srgb);
  EXPECT_THROW(make_sheet(cells, 0, ""), InputError);
  EXPECT_THROW(make_sheet({}, 2, ""), InputError);
}

TEST(ToneMap, AcesIsMonotoneAndBounded) {
  float previous = 0;
  for (int i = 1; i < 200; ++i) {
    const float y = aces_filmic(0.05f * static_cast<float>(i));
    EXPECT_GE(y, previous);
    EXPECT_LE(y, 1.0f);
    previous = y;
  }
  EXPECT_EQ(aces_filmic(-1.0f), 0.0f);
  const Vec3f grey = display_transform(Vec3f(0.18f, 0.18f, 0.18f), 0.0, ToneMap::aces);
  EXPECT_NEAR(grey[0], 0.46f, 0.03f);  // mid-grey stays near sRGB 0.46
  EXPECT_GT(display_transform(Vec3f(0.18f, 0.18f, 0.18f), 1.0, ToneMap::aces)[0], grey[0]);
}

TEST(Text, HaloSurroundsTheGlyphs) {
  Image plain(80, 30, 3, 0.0f, PixelEncoding::srgb);
  Image haloed = plain;
  draw_text(plain, 4, 4, "Go", 18, Vec4f(0.5f, 0.5f, 0.5f, 1));
  draw_text_with_halo(haloed, 4, 4, "Go", 18, Vec4f(0.5f, 0.5f, 0.5f, 1), Vec4f(1, 1, 1, 1), 2.0);
  int lit_plain = 0, lit_haloed = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 80; ++x) {
      lit_plain += plain.at(x, y, 0) > 0.01f ? 1 : 0;
      lit_haloed += haloed.at(x, y, 0) > 0.01f ? 1 : 0;
    }
  EXPECT_GT(lit_haloed, lit_plain + 40);
}
