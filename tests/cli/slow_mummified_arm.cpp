// Slow suite: the small arm phantom mummified by `forensim mummify` (a year at 45 C, 10 % RH and 3 m/s wind, in
// four-day steps: the flesh keeps about an eighth of its water and the skin's moisture ratio falls to about 0.02)
// with the position-based skin and Figure 8's three wrinkle controls on the same drying volume (--figure8).
// Measured properties of the dried skin (Frerichs, Vidler and Gatzidis 2020, sections 2 and 8): no skin triangle
// turned over against its rest normal or passes through another; the skin clings to the shrunk volume over the
// hand and wrist (its mean distance to the bone surface there is within 15 % of the skin glued to the volume) and
// that distance falls by at least half (measured 12.62 -> 6.14 mm). The volume's compression barrier
// (fem/tet_element.hpp) keeps every tet from turning over however far the flesh dries. Figure 8's sets order the
// wrinkles: the dried skin slides and folds within r_max of the volume (eqs. 33 and 35), so the wrinkle height
// grows with r_max (and falls with the damping) by at least 1.3 from set to set (measured 0.075, 0.118 and
// 0.182 mm), and no set's skin turns over or crosses itself.

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

TEST(SlowMummifiedArm, SkinClingsToTheShrunkVolumeAndStaysClean) {
  const auto dir = test::scratch_dir("mummified_arm");
  std::filesystem::remove_all(dir / "run");
  const auto r = run_cli("mummify -o " + (dir / "run").string() +
                         " --days 364 --frames 3 --step-hours 96 --temperature 45 --humidity 10 --wind 3 --figure8 "
                         "--picture-size 160");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::cout << r.output << "\n";
  const auto facts = nlohmann::json::parse(read_file(dir / "run" / "run.json")).at("facts");
  EXPECT_LT(facts.at("water_percent").get<double>(), 20.0);  // fully dried
  EXPECT_EQ(facts.at("inverted_tets"), 0);
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
  double glued = 0.0;
  for (const char* part : {"palm", "wrist"})
    glued += parts.at(part).at("skin_vertices").get<double>() * parts.at(part).at("glued_end_mm").get<double>();
  glued /= count;
  std::printf("hand and wrist skin-to-bone: %.2f mm -> %.2f mm (glued to the volume: %.2f mm)\n", start, end, glued);
  EXPECT_LE(end, 1.15 * glued);
  EXPECT_LE(end, 0.5 * start);

  // A clean surface at the end.
  EXPECT_EQ(facts.at("skin_inverted_triangles"), 0);
  EXPECT_EQ(facts.at("skin_self_intersections"), 0);

  // Figure 8: small, medium and large wrinkles, each set a clean surface.
  const auto& sets = facts.at("figure8");
  ASSERT_EQ(sets.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(sets[k].at("inverted_triangles"), 0) << k;
    EXPECT_EQ(sets[k].at("self_intersections"), 0) << k;
    EXPECT_GT(sets[k].at("wrinkle_height_mm").get<double>(), 0.0) << k;
    // Folds of the skin mesh (about 5 mm edges), not a lift of the whole arm.
    EXPECT_LT(sets[k].at("wrinkle_wavelength_mm").get<double>(), 40.0) << k;
  }
  for (std::size_t k = 1; k < 3; ++k)
    EXPECT_GT(sets[k].at("wrinkle_height_mm").get<double>(), 1.3 * sets[k - 1].at("wrinkle_height_mm").get<double>())
        << "set " << k << " against set " << k - 1;
  EXPECT_TRUE(std::filesystem::exists(dir / "run" / "figure8.png"));
}
