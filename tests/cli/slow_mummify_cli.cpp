#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>

#include "cli/cli_runner.hpp"
#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

// End to end on the small arm phantom: the series, curves, plots, renders and run record are written; water
// is conserved; a run resumed from its checkpoint ends in the same state as one run straight through.
TEST(SlowMummifyCli, RunsWritesOutputsAndResumes) {
  const auto dir = test::scratch_dir("mummify_cli_run");
  std::filesystem::remove_all(dir / "straight");
  std::filesystem::remove_all(dir / "resumed");
  const std::string common = " --days 6 --frames 6 --step-hours 12 --picture-size 96";
  auto r = run_cli("mummify -o " + (dir / "straight").string() + common);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"desiccation.pvd", "volume/frame_0000.vtu", "volume/frame_0006.vtu", "curves.csv", "curves.png",
                        "curves_parts.png", "moisture_outside.png", "moisture_cut.png", "shrinkage.png",
                        "mummify_sheet.png", "run.json", "checkpoint.bin"})
    EXPECT_TRUE(std::filesystem::exists(dir / "straight" / f)) << f;
  const auto record = nlohmann::json::parse(read_file(dir / "straight" / "run.json"));
  EXPECT_EQ(record["command"], "mummify");
  EXPECT_EQ(record["facts"]["inverted_tets"], 0);
  EXPECT_LT(record["facts"]["mass_percent"].get<double>(), 100.0);
  EXPECT_NEAR(record["facts"]["water_balance_error_kg"].get<double>(), 0.0, 1e-8);

  // First half (3 days), then resume from its checkpoint to day 6.
  r = run_cli("mummify -o " + (dir / "resumed").string() + " --days 3 --frames 3 --step-hours 12 --no-pictures");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("mummify -o " + (dir / "resumed").string() +
              " --days 6 --frames 6 --step-hours 12 --no-pictures --resume");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("resuming at day 3"), std::string::npos) << r.output;
  // The same output frames (so the same steps with a shape solve): the final state is bit-identical.
  EXPECT_EQ(read_file(dir / "resumed" / "checkpoint.bin"), read_file(dir / "straight" / "checkpoint.bin"));
}
