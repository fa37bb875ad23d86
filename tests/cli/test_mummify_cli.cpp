#include <gtest/gtest.h>

#include <filesystem>

#include "cli/cli_runner.hpp"
#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

// The job file is checked before anything is built or written: unknown keys, wrong types and values out of
// range are job errors (exit code 4) naming the key.
TEST(MummifyCli, RejectsBadJobsBeforeWriting) {
  const auto dir = test::scratch_dir("mummify_cli_jobs");
  const auto out = dir / "out";
  std::filesystem::remove_all(out);
  write_file_atomic(dir / "typo.json", R"({"days": 3, "environment": {"humidty_percent": 20}})");
  auto r = run_cli("mummify " + (dir / "typo.json").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("humidty_percent"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out / "run.json"));

  write_file_atomic(dir / "range.json", R"({"environment": {"humidity_percent": 300}})");
  r = run_cli("mummify " + (dir / "range.json").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("humidity_percent"), std::string::npos) << r.output;

  write_file_atomic(dir / "type.json", R"({"body": {"phantom": "leg"}})");
  r = run_cli("mummify " + (dir / "type.json").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 4) << r.output;

  write_file_atomic(dir / "broken.json", R"({"days": )");
  r = run_cli("mummify " + (dir / "broken.json").string() + " -o " + out.string());
  EXPECT_NE(r.exit_code, 0) << r.output;
}

TEST(MummifyCli, RejectsBadArguments) {
  const auto out = test::scratch_dir("mummify_cli_args") / "out";
  EXPECT_EQ(run_cli("mummify --humidity 150 -o " + out.string()).exit_code, 2);
  EXPECT_EQ(run_cli("mummify --phantom leg -o " + out.string()).exit_code, 2);
  const auto missing = run_cli("mummify /no/such/job.json -o " + out.string());
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(run_cli("mummify --help").output.find("--resume"), std::string::npos);
}

// The skin shading settings go through the same job loader: unknown keys and bad values in "skin" are job
// errors naming the key, before anything is built or written.
TEST(MummifyCli, RejectsBadSkinShadingKeys) {
  const auto dir = test::scratch_dir("mummify_cli_skin_jobs");
  const auto out = dir / "out";
  std::filesystem::remove_all(out);
  const std::pair<const char*, const char*> cases[] = {
      {R"({"skin": {"gravty": [0, 0, -1]}})", "gravty"},
      {R"({"skin": {"gravity": [0, 0]}})", "gravity"},
      {R"({"skin": {"gravity": [0, 0, 0]}})", "gravity"},
      {R"({"skin": {"gravity": "down"}})", "gravity"},
      {R"({"skin": {"contact_distance_mm": 5000}})", "contact_distance_mm"},
      {R"({"skin": {"map_resolution": 8}})", "map_resolution"},
      {R"({"skin": {"drying_boost": 9}})", "drying_boost"},
      {R"({"skin": {"blood_fill": 0.2, "residual_fill": 0.3}})", "residual_fill"},
      {R"({"skin": {"oxygen_decay_hours": 0}})", "oxygen_decay_hours"},
  };
  for (const auto& [json, key] : cases) {
    write_file_atomic(dir / "skin.json", json);
    const auto r = run_cli("mummify " + (dir / "skin.json").string() + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 4) << json << "\n" << r.output;
    EXPECT_NE(r.output.find(key), std::string::npos) << json << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(out / "run.json")) << json;
  }
  // CLI flags for the common ones: --gravity takes exactly three numbers.
  EXPECT_EQ(run_cli("mummify --gravity 0 -1 -o " + out.string()).exit_code, 2);
  EXPECT_EQ(run_cli("mummify --contact-mm 5000 -o " + out.string()).exit_code, 2);
  const std::string help = run_cli("mummify --help").output;
  for (const char* flag : {"--gravity", "--contact-mm", "--map-size"})
    EXPECT_NE(help.find(flag), std::string::npos) << flag;
}

// The position-based skin's settings ("skin": "pbd", "wrinkle", "iterations", "substeps", "slippage", ...) are
// checked by the same loader: job errors naming the key, before anything is built or written.
TEST(MummifyCli, RejectsBadSkinMotionKeys) {
  const auto dir = test::scratch_dir("mummify_cli_skin_motion_jobs");
  const auto out = dir / "out";
  std::filesystem::remove_all(out);
  const std::pair<const char*, const char*> cases[] = {
      {R"({"skin": {"pbd": "yes"}})", "pbd"},
      {R"({"skin": {"wrinkle": {"set": 3}}})", "set"},
      {R"({"skin": {"wrinkle": {"set": 1, "damping": 0.3}}})", "set"},
      {R"({"skin": {"wrinkle": {"sett": 1}}})", "sett"},
      {R"({"skin": {"wrinkle": {"r_max_relative": -0.001}}})", "r_max_relative"},
      {R"({"skin": {"wrinkle": {"damping": 1.5}}})", "damping"},
      {R"({"skin": {"wrinkle": 2}})", "wrinkle"},
      {R"({"skin": {"iterations": 0}})", "iterations"},
      {R"({"skin": {"substeps": 0}})", "substeps"},
      {R"({"skin": {"bending_interval": 0}})", "bending_interval"},
      {R"({"skin": {"skin_shrinkage": 0.95}})", "skin_shrinkage"},
      {R"({"skin": {"slippage": {"decrease_below": 0.1, "zero_below": 0.2}}})", "zero_below"},
      {R"({"skin": {"slippage": {"stiffness": 2}}})", "stiffness"},
  };
  for (const auto& [json, key] : cases) {
    write_file_atomic(dir / "skin.json", json);
    const auto r = run_cli("mummify " + (dir / "skin.json").string() + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 4) << json << "\n" << r.output;
    EXPECT_NE(r.output.find(key), std::string::npos) << json << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(out / "run.json")) << json;
  }
  EXPECT_EQ(run_cli("mummify --wrinkle-set 3 -o " + out.string()).exit_code, 2);
  EXPECT_NE(run_cli("mummify --help").output.find("--wrinkle-set"), std::string::npos);
}
