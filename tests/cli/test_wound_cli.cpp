// End-to-end tests of `forensim wound`: a small run writes its maps, GLBs, renders and timeline; bad input
// exits non-zero naming the problem and writes nothing.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

namespace {
const char* kSmall = "wound --builtin cylinder --resolution 128 --samples 1 ";

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}
}  // namespace

TEST(WoundCli, WritesMapsGlbRendersAndTimeline) {
  const auto dir = test::scratch_dir("wound_cli_run");
  const auto out = dir / "run";
  const auto r = run_cli(std::string(kSmall) + "--times 36h,2w --seed 3 --picture-size 48 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f :
       {"timeline.json", "run.json", "maps/key0_vasoconstriction_color.png", "maps/key0_vasoconstriction_height.exr",
        "maps/key5_scab_height.exr", "maps/key5_scab_normal.png", "maps/time_1.5d_color.png", "wound_time_1.5d.glb",
        "wound_time_2w.glb", "timeline_keys.png", "timeline_times.png", "overview.png"}) {
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  }
  const auto timeline = nlohmann::json::parse(read_file(out / "timeline.json"));
  EXPECT_EQ(timeline["type"], "abrasion");
  EXPECT_EQ(timeline["entries"].size(), 9u);
  EXPECT_EQ(timeline["entries"][7]["instant_cut"], true);
  EXPECT_EQ(timeline["time_files"].size(), 2u);
  // Same seed, same maps.
  const auto again = dir / "again";
  ASSERT_EQ(run_cli(std::string(kSmall) + "--times 36h,2w --seed 3 --picture-size 0 -o " + again.string()).exit_code,
            0);
  EXPECT_EQ(read_file(out / "maps/key5_scab_color.png"), read_file(again / "maps/key5_scab_color.png"));
  // A bruise through the same command.
  const auto bruise = dir / "bruise";
  const auto b = run_cli(std::string(kSmall) + "--type bruise --times 5d --picture-size 0 -o " + bruise.string());
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_TRUE(std::filesystem::exists(bruise / "maps/key2_green_color.png"));
}

TEST(WoundCli, BadInputExitsNonZeroNamingTheProblemAndWritesNothing) {
  const auto dir = test::scratch_dir("wound_cli_bad");
  // Unknown key in the job.
  write_text(dir / "typo.json", R"({"strokes": [{"uv": [[0.5, 0.3]], "raduis_mm": 2}]})");
  auto r = run_cli(std::string(kSmall) + "--strokes " + (dir / "typo.json").string() + " -o " + (dir / "a").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("raduis_mm"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "a"));
  // Strokes off the mesh.
  write_text(dir / "off.json", R"({"strokes": [{"points": [[500, 0, 30]], "radius_mm": 2}]})");
  r = run_cli(std::string(kSmall) + "--strokes " + (dir / "off.json").string() + " -o " + (dir / "b").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("off the mesh"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "b"));
  // A mesh without UVs.
  write_text(dir / "tri.obj", "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 3\n");
  r = run_cli(std::string(kSmall) + "--mesh " + (dir / "tri.obj").string() + " -o " + (dir / "c").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("UVs"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "c"));
  // A bad time.
  r = run_cli(std::string(kSmall) + "--times 3days -o " + (dir / "d").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("3days"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "d"));
}

TEST(WoundCli, BenchTimesEachPhaseAllPhasesAndATimelineSample) {
  const auto dir = test::scratch_dir("wound_cli_bench");
  const auto json = dir / "bench.json";
  const auto r = run_cli("bench wound --size small --repeat 1 --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto out = nlohmann::json::parse(read_file(json));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0]["target"], "wound");
  std::vector<std::string> steps;
  for (const auto& row : out[0]["rows"]) {
    steps.push_back(row["step"]);
    EXPECT_GT(row["median_s"].get<double>(), 0.0) << row["step"];
  }
  for (const char* step : {"vasoconstriction 1024^2", "vasodilation 1024^2", "scab_forming 1024^2", "scab 1024^2",
                           "maturation 1024^2", "all phases 1024^2", "timeline sample 1024^2"}) {
    EXPECT_NE(std::find(steps.begin(), steps.end(), step), steps.end()) << step;
  }
}
