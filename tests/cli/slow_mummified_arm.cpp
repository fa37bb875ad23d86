// Slow suite: the small arm phantom mummified by `forensim mummify` (60 days at 45 C, 10 % RH and 3 m/s wind: the
// flesh keeps under a third of its water and about half its volume) with the position-based skin and Figure 8's
// three wrinkle controls on the same drying volume (--figure8). Measured properties of the dried skin (Frerichs,
// Vidler and Gatzidis 2020, sections 2 and 8): it clings to the bones of the hand and wrist (the mean distance of
// their skin vertices to the bone surface falls by at least half), no skin triangle turned over against its rest
// normal or passes through another, and the wrinkle height grows from set to set by a clear margin.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli/cli_runner.hpp"
#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

TEST(SlowMummifiedArm, SkinClingsToTheBonesStaysCleanAndFigure8SetsWrinkleMore) {
  const auto dir = test::scratch_dir("mummified_arm");
  std::filesystem::remove_all(dir / "run");
  const auto r = run_cli("mummify -o " + (dir / "run").string() +
                         " --days 60 --frames 3 --step-hours 24 --temperature 45 --humidity 10 --wind 3 --figure8 "
                         "--picture-size 160");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::cout << r.output << "\n";
  const auto facts = nlohmann::json::parse(read_file(dir / "run" / "run.json")).at("facts");
  EXPECT_LT(facts.at("water_percent").get<double>(), 35.0);  // fully dried, as far as the volume goes
  EXPECT_EQ(facts.at("skin_pbd"), true);

  // Hand (palm) and wrist: the mean skin-to-bone distance over their skin vertices, start and end.
  const auto& parts = facts.at("skin_bone_distance");
  double start = 0.0, end = 0.0, count = 0.0;
  for (const char* part : {"palm", "wrist"}) {
    ASSERT_TRUE(parts.contains(part)) << part;
    const double n = parts.at(part).at("skin_vertices").get<double>();
    start += n * parts.at(part).at("start_mm").get<double>();
    end += n * parts.at(part).at("end_mm").get<double>();
    count += n;
  }
  ASSERT_GT(count, 0.0);
  start /= count;
  end /= count;
  std::printf("hand and wrist skin-to-bone: %.2f mm -> %.2f mm\n", start, end);
  EXPECT_LE(end, 0.5 * start);

  // A clean surface at the end.
  EXPECT_EQ(facts.at("skin_inverted_triangles"), 0);
  EXPECT_EQ(facts.at("skin_self_intersections"), 0);

  // Figure 8: each set wrinkles at least 1.2 times as much as the one before, none turns a triangle over.
  const auto& sets = facts.at("figure8");
  ASSERT_EQ(sets.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(sets[k].at("inverted_triangles"), 0) << k;
  for (std::size_t k = 1; k < 3; ++k)
    EXPECT_GE(sets[k].at("wrinkle_height_mm").get<double>(), 1.2 * sets[k - 1].at("wrinkle_height_mm").get<double>())
        << "set " << k;
  EXPECT_GT(sets[0].at("wrinkle_height_mm").get<double>(), 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "run" / "figure8.png"));
}
