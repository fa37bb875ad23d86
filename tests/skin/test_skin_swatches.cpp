// Swatches of the shader's stages (fresh, livor, drying, green stage, dried) against the committed pictures
// tests/golden/skin/swatch_strip.png (swatches only, strict) and swatch_sheet.png (with captions). After an
// intended change of the look, regenerate them with FORENSIM_UPDATE_GOLDEN=1 and look at them.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "image/png_io.hpp"
#include "render/sheet.hpp"
#include "skin/skin_swatches.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

std::vector<SheetCell> swatch_cells() {
  const SkinShader shader;
  const SkinLayers layers = uniform_skin_layers(1);
  std::vector<SheetCell> cells;
  for (const SkinStage& stage : default_skin_stages(shader))
    cells.push_back({make_skin_swatch(shader, layers, stage, 52, 64), stage.caption});
  return cells;
}

Image swatch_sheet(const std::vector<SheetCell>& cells) {
  SheetStyle style;
  style.caption_px = 11;
  style.title_px = 14;
  style.padding = 6;
  return make_sheet(cells, 7, "skin stages: blanched (top) to livid (bottom)", style);
}

// The swatches side by side without text: compared strictly, since no font is involved.
Image swatch_strip(const std::vector<SheetCell>& cells) {
  Image strip(52 * static_cast<int>(cells.size()), 64, 3, 0.0f, PixelEncoding::srgb);
  for (std::size_t i = 0; i < cells.size(); ++i) strip.paste(cells[i].image, 52 * static_cast<int>(i), 0);
  return strip;
}

// Compares with tests/golden/skin/<name>.png (8-bit display values): mean absolute difference below
// `max_mean` codes and at most `max_far_fraction` of the pixels off by more than `far_codes`.
void expect_matches_golden(const Image& picture, const std::string& name, double max_mean, double far_codes,
                           double max_far_fraction) {
  const std::filesystem::path path = test::tests_dir() / "golden/skin" / (name + ".png");
  const char* update = std::getenv("FORENSIM_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    std::filesystem::create_directories(path.parent_path());
    write_png(path, picture);
    GTEST_SKIP() << "updated " << path;
  }
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing: run with FORENSIM_UPDATE_GOLDEN=1";
  const Image golden = read_png(path, PngTransfer::identity);
  ASSERT_EQ(golden.width(), picture.width());
  ASSERT_EQ(golden.height(), picture.height());
  ASSERT_EQ(golden.channels(), picture.channels());
  double total = 0.0;
  int far = 0;
  for (int y = 0; y < picture.height(); ++y)
    for (int x = 0; x < picture.width(); ++x) {
      double worst = 0.0;
      for (int c = 0; c < picture.channels(); ++c) {
        const double d = std::abs(std::round(picture.at(x, y, c) * 255.0) - golden.at(x, y, c) * 255.0);
        total += d;
        worst = std::max(worst, d);
      }
      if (worst > far_codes) ++far;
    }
  const double pixels = static_cast<double>(picture.width()) * picture.height();
  const double mean = total / (pixels * picture.channels());
  EXPECT_LT(mean, max_mean) << name << ": mean absolute difference " << mean << " codes";
  EXPECT_LE(far, max_far_fraction * pixels) << name << ": " << far << " pixels differ by more than " << far_codes;
}

}  // namespace

TEST(SkinSwatches, StagesReadAsDesigned) {
  const SkinShader shader;
  const SkinLayers layers = uniform_skin_layers(1);
  const std::vector<SkinStage> stages = default_skin_stages(shader);
  ASSERT_EQ(stages.size(), 7u);
  const Image livor = make_skin_swatch(shader, layers, stages[1], 4, 32);
  const Image dried = make_skin_swatch(shader, layers, stages.back(), 4, 32);
  EXPECT_EQ(livor.encoding(), PixelEncoding::srgb);
  // Livor: livid bottom darker than the pale top; dried: darker than livor throughout.
  EXPECT_LT(livor.at(0, 31, 0), livor.at(0, 0, 0) - 0.05f);  // red falls most: bluish purple
  for (int y = 0; y < 32; y += 4) EXPECT_LT(dried.at(0, y, 1), livor.at(0, y, 1)) << y;
}

TEST(SkinSwatches, SwatchesMatchGolden) {
  // Every swatch pixel within 2 codes (libm differences between machines).
  expect_matches_golden(swatch_strip(swatch_cells()), "swatch_strip", 0.5, 2.0, 0.0);
}

TEST(SkinSwatches, SheetMatchesGolden) {
  // With captions and title: the renderer's golden tolerance for text (see tests/render/test_golden_images.cpp).
  expect_matches_golden(swatch_sheet(swatch_cells()), "swatch_sheet", 1.5, 24.0, 0.01);
}
