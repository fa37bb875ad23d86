#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

#include "cli/cli_runner.hpp"
#include "cli/glb_reader.hpp"
#include "core/atomic_file.hpp"
#include "core/types.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

namespace {

/// Per frame node of skin.glb: the mean of its COLOR_0 (linear RGB).
std::vector<Vec3> frame_mean_colours(const test::Glb& glb) {
  std::vector<Vec3> means;
  for (const auto& node : glb.json.at("nodes")) {
    const auto& primitive = glb.json.at("meshes").at(node.at("mesh").get<std::size_t>()).at("primitives").at(0);
    const std::vector<float> rgba = glb.floats(primitive.at("attributes").at("COLOR_0").get<int>());
    Vec3 sum = Vec3::Zero();
    for (std::size_t i = 0; i + 3 < rgba.size(); i += 4) sum += Vec3(rgba[i], rgba[i + 1], rgba[i + 2]);
    means.push_back(sum / std::max<double>(1.0, static_cast<double>(rgba.size() / 4)));
  }
  return means;
}

double luminance(const Vec3& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

}  // namespace

// End to end on the small arm phantom: the series, curves, plots, renders and run record are written; water
// is conserved; the position-based skin moved off the volume it was glued to; a run resumed from its
// checkpoint (the desiccation and the skin state, each half on another thread count) ends in the same state
// as one run straight through, and writes the same skin frames and animated skin; a run on 1 thread writes the
// same as one on 2.
TEST(SlowMummifyCli, RunsWritesOutputsAndResumes) {
  const auto dir = test::scratch_dir("mummify_cli_run");
  for (const char* run : {"straight", "resumed", "one_thread", "glued"}) std::filesystem::remove_all(dir / run);
  const std::string common = " --days 6 --frames 6 --step-hours 12 --picture-size 96";
  auto r = run_cli("--threads 2 mummify -o " + (dir / "straight").string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"desiccation.pvd", "volume/frame_0000.vtu", "volume/frame_0006.vtu", "curves.csv", "curves.png",
                        "curves_parts.png", "moisture_outside.png", "moisture_cut.png", "shrinkage.png",
                        "mummify_sheet.png", "run.json", "checkpoint.bin", "skin.glb", "skin.pvd",
                        "skin/frame_0000.vtu", "skin/frame_0006.vtu", "skin_timeline.png", "skin_turntable.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "straight" / f)) << f;
  const auto record = nlohmann::json::parse(read_file(dir / "straight" / "run.json"));
  EXPECT_EQ(record["command"], "mummify");
  EXPECT_EQ(record["facts"]["inverted_tets"], 0);
  EXPECT_LT(record["facts"]["mass_percent"].get<double>(), 100.0);
  EXPECT_NEAR(record["facts"]["water_balance_error_kg"].get<double>(), 0.0, 1e-8);
  EXPECT_EQ(record["facts"]["skin_frames"], 7);
  EXPECT_EQ(record["facts"]["skin_pbd"], true);
  EXPECT_GT(record["facts"]["skin_steps"].get<long long>(), 0);

  // The GLB: one node per frame (start + 6), each but the last with one morph target to the next frame, and one
  // clip "drying" of 6 weight channels (0 -> 1 while the frame is shown) and 7 STEP scale channels.
  const test::Glb glb = test::parse_glb(read_file(dir / "straight" / "skin.glb"));
  ASSERT_EQ(glb.json.at("nodes").size(), 7u);
  for (std::size_t k = 0; k < 7; ++k) {
    const auto& mesh = glb.json.at("meshes").at(glb.json.at("nodes")[k].at("mesh").get<std::size_t>());
    const auto& primitive = mesh.at("primitives").at(0);
    EXPECT_EQ(primitive.value("targets", nlohmann::json::array()).size(), k < 6 ? 1u : 0u) << k;
    EXPECT_TRUE(primitive.at("attributes").contains("COLOR_0")) << k;
    EXPECT_TRUE(primitive.at("attributes").contains("NORMAL")) << k;
  }
  ASSERT_EQ(glb.json.at("animations").size(), 1u);
  const auto& clip = glb.json.at("animations")[0];
  EXPECT_EQ(clip.at("name"), "drying");
  int weights = 0, scales = 0;
  for (const auto& channel : clip.at("channels")) {
    const auto& sampler = clip.at("samplers").at(channel.at("sampler").get<std::size_t>());
    const std::vector<float> out = glb.floats(sampler.at("output").get<int>());
    if (channel.at("target").at("path") == "weights") {
      ++weights;
      EXPECT_EQ(out, (std::vector<float>{0.0f, 1.0f}));
    } else {
      ++scales;
      EXPECT_EQ(sampler.at("interpolation"), "STEP");
      EXPECT_EQ(out.size(), 21u);  // 7 keyframes of xyz
    }
  }
  EXPECT_EQ(weights, 6);
  EXPECT_EQ(scales, 7);
  const std::vector<Vec3> colours = frame_mean_colours(glb);
  EXPECT_LT(luminance(colours.back()), luminance(colours.front()));  // drying skin darkens

  // First half (3 days), then resume from its checkpoint to day 6.
  // The halves run on 1 and 2 worker threads (the straight run on 2): output must not depend on it.
  r = run_cli("--threads 1 mummify -o " + (dir / "resumed").string() +
              " --days 3 --frames 3 --step-hours 12 --no-pictures");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("--threads 2 mummify -o " + (dir / "resumed").string() +
              " --days 6 --frames 6 --step-hours 12 --no-pictures --resume");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("resuming at day 3"), std::string::npos) << r.output;
  // The same output frames (so the same steps with a shape solve): the final state is bit-identical.
  EXPECT_EQ(read_file(dir / "resumed" / "checkpoint.bin"), read_file(dir / "straight" / "checkpoint.bin"));
  EXPECT_EQ(read_file(dir / "resumed" / "skin.glb"), read_file(dir / "straight" / "skin.glb"));
  // The skin's positions at every frame after the resumption come from the restored skin state.
  for (const char* f : {"skin/frame_0004.vtu", "skin/frame_0005.vtu", "skin/frame_0006.vtu"})
    EXPECT_EQ(read_file(dir / "resumed" / f), read_file(dir / "straight" / f)) << f;

  // The whole run on one worker thread writes the same skin and state as on two.
  r = run_cli("--threads 1 mummify -o " + (dir / "one_thread").string() +
              " --days 6 --frames 6 --step-hours 12 "
              "--no-pictures");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_file(dir / "one_thread" / "checkpoint.bin"), read_file(dir / "straight" / "checkpoint.bin"));
  for (int k = 0; k <= 6; ++k) {
    const std::string f = "skin/frame_000" + std::to_string(k) + ".vtu";
    EXPECT_EQ(read_file(dir / "one_thread" / f), read_file(dir / "straight" / f)) << f;
  }

  // With "pbd": false the skin is glued to the volume; the position-based skin is not (it lifts off and wrinkles),
  // and resuming a glued run's checkpoint with the position-based skin is refused.
  write_file_atomic(dir / "glued.json", R"({"skin": {"pbd": false}})");
  r = run_cli("mummify " + (dir / "glued.json").string() + " -o " + (dir / "glued").string() +
              " --days 6 --frames 6 --step-hours 12 --no-pictures");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto glued = nlohmann::json::parse(read_file(dir / "glued" / "run.json"))["facts"];
  EXPECT_EQ(glued["skin_pbd"], false);
  EXPECT_EQ(glued["skin_wrinkle_height_mm"].get<double>(), 0.0);
  EXPECT_GT(record["facts"]["skin_wrinkle_height_mm"].get<double>(), 0.0);
  EXPECT_NE(read_file(dir / "glued" / "skin/frame_0006.vtu"), read_file(dir / "straight" / "skin/frame_0006.vtu"));
  r = run_cli("mummify -o " + (dir / "glued").string() + " --days 8 --frames 8 --step-hours 12 --no-pictures --resume");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("position-based"), std::string::npos) << r.output;
}

// Two months of drying: the skin's frames in the GLB get darker and browner (less blue against red) from the
// livor mortis start state to the dried end, and the run's facts say the same of the area-weighted means.
TEST(SlowMummifyCli, SkinDarkensAndBrownsAsItDries) {
  const auto dir = test::scratch_dir("mummify_cli_skin_colour");
  std::filesystem::remove_all(dir / "run");
  const auto r =
      run_cli("mummify -o " + (dir / "run").string() + " --days 60 --frames 2 --step-hours 48 --no-pictures");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const test::Glb glb = test::parse_glb(read_file(dir / "run" / "skin.glb"));
  const std::vector<Vec3> colours = frame_mean_colours(glb);
  ASSERT_EQ(colours.size(), 3u);
  for (std::size_t k = 1; k < colours.size(); ++k) {
    EXPECT_LT(luminance(colours[k]), luminance(colours[k - 1])) << k;
  }
  const Vec3 fresh = colours.front(), dried = colours.back();
  EXPECT_LT(luminance(dried), 0.8 * luminance(fresh));
  EXPECT_LT(dried[2] / dried[0], 0.95 * fresh[2] / fresh[0]);  // browner: blue falls faster than red
  EXPECT_GT(dried[0], dried[1]);
  EXPECT_GT(dried[1], dried[2]);
  const auto facts = nlohmann::json::parse(read_file(dir / "run" / "run.json"))["facts"];
  EXPECT_LT(facts["skin_mean_moisture_end"].get<double>(), 0.6);
  EXPECT_LT(facts["skin_mean_colour_end"][2].get<double>(), facts["skin_mean_colour_start"][2].get<double>());
}
