// Quick end-to-end tests of `forensim reconstruct`: bad input exits with its error kind's code and a message
// naming the input, and writes nothing. (These inputs are checked before the template head is built; runs
// that reconstruct a head are in slow_reconstruct.cpp.)

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "core/error.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

namespace {

const char* kSmall = "reconstruct --template-detail coarse --texture-size 64 --picture-size 0 ";

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

int code(ErrorKind kind) {
  return static_cast<int>(kind);
}

}  // namespace

TEST(ReconstructCli, UnknownTableExitsWithInputCodeNamingIt) {
  const auto dir = test::scratch_dir("reconstruct_cli_table");
  const auto r = run_cli(std::string(kSmall) + "--table ttable_2032 -o " + (dir / "run").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("ttable_2032"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ttable_2023"), std::string::npos) << r.output;  // the suggestion
  EXPECT_FALSE(std::filesystem::exists(dir / "run"));
  // A table file with a negative depth names the file and the line.
  write_text(dir / "mine.csv", "landmark,mean_mm,sex,population,build,source\nn,-3,pooled,pooled,pooled,mine\n");
  const auto t =
      run_cli(std::string(kSmall) + "--table " + (dir / "mine.csv").string() + " -o " + (dir / "run2").string());
  EXPECT_EQ(t.exit_code, code(ErrorKind::input)) << t.output;
  EXPECT_NE(t.output.find("mine.csv"), std::string::npos) << t.output;
  EXPECT_NE(t.output.find("line 2"), std::string::npos) << t.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "run2"));
}

TEST(ReconstructCli, UnknownOrRepeatedExpressionsExitNamingThem) {
  const auto dir = test::scratch_dir("reconstruct_cli_expressions");
  auto r = run_cli(std::string(kSmall) + "--expressions smile,grin -o " + (dir / "a").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("grin"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "a"));
  r = run_cli(std::string(kSmall) + "--expressions smile,,frown -o " + (dir / "b").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("--expressions"), std::string::npos) << r.output;
  write_text(dir / "repeat.json", R"({"expressions": ["smile", "frown", "smile"]})");
  r = run_cli(std::string(kSmall) + "--job " + (dir / "repeat.json").string() + " -o " + (dir / "c").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::job)) << r.output;
  EXPECT_NE(r.output.find("expressions"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("twice"), std::string::npos) << r.output;
  write_text(dir / "wrong.json", R"({"expressions": "smile"})");
  r = run_cli(std::string(kSmall) + "--job " + (dir / "wrong.json").string() + " -o " + (dir / "d").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::job)) << r.output;
  for (const char* run : {"b", "c", "d"}) EXPECT_FALSE(std::filesystem::exists(dir / run)) << run;
}

TEST(ReconstructCli, BadLandmarkFilesExitNamingTheFile) {
  const auto dir = test::scratch_dir("reconstruct_cli_landmarks");
  // An unknown label in a markups file.
  write_text(dir / "bad.mrk.json", R"({"markups": [{"type": "Fiducial", "coordinateSystem": "LPS",
      "controlPoints": [{"label": "nasoin_x", "position": [0, -90, 30], "positionStatus": "defined"}]}]})");
  auto r =
      run_cli(std::string(kSmall) + "--landmarks " + (dir / "bad.mrk.json").string() + " -o " + (dir / "a").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("bad.mrk.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("nasoin_x"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "a"));
  // Invalid JSON.
  write_text(dir / "broken.mrk.json", R"({"markups": [)");
  r = run_cli(std::string(kSmall) + "--landmarks " + (dir / "broken.mrk.json").string() + " -o " +
              (dir / "b").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("broken.mrk.json"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "b"));
  // A CSV row with a non-numeric coordinate.
  write_text(dir / "bad.csv", "name,x,y,z\nn,0,-90,abc\n");
  r = run_cli(std::string(kSmall) + "--landmarks " + (dir / "bad.csv").string() + " -o " + (dir / "c").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("bad.csv"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "c"));
  // A file that does not exist.
  r = run_cli(std::string(kSmall) + "--landmarks " + (dir / "none.mrk.json").string() + " -o " + (dir / "d").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::io)) << r.output;
  EXPECT_NE(r.output.find("none.mrk.json"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "d"));
}

TEST(ReconstructCli, TemplateLandmarksOnAnotherSkullExitNamingTheOption) {
  const auto dir = test::scratch_dir("reconstruct_cli_template_landmarks");
  write_text(dir / "tri.obj", "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 3\n");
  const auto r = run_cli(std::string(kSmall) + "--skull " + (dir / "tri.obj").string() + " --landmarks template -o " +
                         (dir / "run").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("--landmarks"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'auto'"), std::string::npos) << r.output;  // the way out
  EXPECT_FALSE(std::filesystem::exists(dir / "run"));
}

TEST(ReconstructCli, JobFileWithUnknownKeyOrBadValueExitsWithJobCode) {
  const auto dir = test::scratch_dir("reconstruct_cli_job");
  write_text(dir / "typo.json", R"({"version": 1, "tabel": "ttable_2023"})");
  auto r = run_cli(std::string(kSmall) + "--job " + (dir / "typo.json").string() + " -o " + (dir / "a").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::job)) << r.output;
  EXPECT_NE(r.output.find("tabel"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("typo.json"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "a"));
  // A misspelt guide and a wrong build name inside the job.
  write_text(dir / "guides.json", R"({"guides": {"lip_partng_mm": -40}})");
  r = run_cli(std::string(kSmall) + "--job " + (dir / "guides.json").string() + " -o " + (dir / "b").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::job)) << r.output;
  EXPECT_NE(r.output.find("lip_partng_mm"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "b"));
  write_text(dir / "build.json", R"({"build": "athletic"})");
  r = run_cli(std::string(kSmall) + "--job " + (dir / "build.json").string() + " -o " + (dir / "c").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::job)) << r.output;
  EXPECT_NE(r.output.find("athletic"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "c"));
  // An ensemble of one member, and a misspelt key inside the uncertainty object.
  write_text(dir / "one.json", R"({"uncertainty": {"samples": 1}})");
  r = run_cli(std::string(kSmall) + "--job " + (dir / "one.json").string() + " -o " + (dir / "e").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::job)) << r.output;
  EXPECT_NE(r.output.find("samples"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "e"));
  write_text(dir / "seeds.json", R"({"uncertainty": {"samples": 4, "seeds": 2}})");
  r = run_cli(std::string(kSmall) + "--job " + (dir / "seeds.json").string() + " -o " + (dir / "f").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::job)) << r.output;
  EXPECT_NE(r.output.find("seeds"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "f"));
  // A guides file with a vector of two numbers.
  write_text(dir / "g.json", R"({"nasal_spine_tip": [1, 2]})");
  r = run_cli(std::string(kSmall) + "--guides " + (dir / "g.json").string() + " -o " + (dir / "d").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::job)) << r.output;
  EXPECT_NE(r.output.find("nasal_spine_tip"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "d"));
}

TEST(ReconstructCli, EvaluateRefusesASkullWithoutAFace) {
  const auto dir = test::scratch_dir("reconstruct_cli_evaluate");
  const auto r = run_cli(std::string(kSmall) + "--evaluate -o " + (dir / "run").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("--evaluate"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("skin"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "run"));
  write_text(dir / "skull.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const auto m = run_cli(std::string(kSmall) + "--evaluate --skull " + (dir / "skull.obj").string() + " -o " +
                         (dir / "run2").string());
  EXPECT_EQ(m.exit_code, code(ErrorKind::input)) << m.output;
  EXPECT_NE(m.output.find("skull.obj"), std::string::npos) << m.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "run2"));
}
