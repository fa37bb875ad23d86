// Swatch sheet of the shader's stages (fresh, livor, drying, green stage, dried) against the committed picture
// tests/golden/skin/swatch_sheet.png. After an intended change of the look, regenerate it with
// FORENSIM_UPDATE_GOLDEN=1 and look at it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "image/png_io.hpp"
#include "render/sheet.hpp"
#include "skin/skin_swatches.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

Image swatch_sheet() {
  const SkinShader shader;
  const SkinLayers layers = uniform_skin_layers(1);
  std::vector<SheetCell> cells;
  for (const SkinStage& stage : default_skin_stages(shader))
    cells.push_back({make_skin_swatch(shader, layers, stage, 52, 64), stage.caption});
  SheetStyle style;
  style.caption_px = 11;
  style.title_px = 14;
  style.padding = 6;
  return make_sheet(cells, 7, "skin stages: blanched (top) to livid (bottom)", style);
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

TEST(SkinSwatches, SheetMatchesGolden) {
  const Image sheet = swatch_sheet();
  const std::filesystem::path path = test::tests_dir() / "golden/skin/swatch_sheet.png";
  const char* update = std::getenv("FORENSIM_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    std::filesystem::create_directories(path.parent_path());
    write_png(path, sheet);
    GTEST_SKIP() << "updated " << path;
  }
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing: run with FORENSIM_UPDATE_GOLDEN=1";
  const Image golden = read_png(path, PngTransfer::identity);
  ASSERT_EQ(golden.width(), sheet.width());
  ASSERT_EQ(golden.height(), sheet.height());
  ASSERT_EQ(golden.channels(), sheet.channels());
  double total = 0.0, worst = 0.0;
  for (int y = 0; y < sheet.height(); ++y)
    for (int x = 0; x < sheet.width(); ++x)
      for (int c = 0; c < sheet.channels(); ++c) {
        const double d = std::abs(std::round(sheet.at(x, y, c) * 255.0) - golden.at(x, y, c) * 255.0);
        total += d;
        worst = std::max(worst, d);
      }
  const double mean = total / (static_cast<double>(sheet.width()) * sheet.height() * sheet.channels());
  EXPECT_LT(mean, 0.5) << "mean absolute difference " << mean << " codes";
  EXPECT_LE(worst, 3.0) << "largest difference " << worst << " codes";  // text anti-aliasing, rounding
}
