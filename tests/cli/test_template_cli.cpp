// Quick end-to-end tests of `forensim template build` and `forensim reconstruct --template`: bad input exits with
// its error kind's code and a message naming the input, and writes nothing.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/cli_runner.hpp"
#include "core/error.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

namespace {

int code(ErrorKind kind) {
  return static_cast<int>(kind);
}

}  // namespace

TEST(TemplateCli, BuildNeedsOneHeadAndSaysWhich) {
  const auto dir = test::scratch_dir("template_cli_usage");
  auto r = run_cli("template build -o " + (dir / "a").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::usage)) << r.output;
  EXPECT_NE(r.output.find("--ct"), std::string::npos) << r.output;
  r = run_cli("template build --ct phantom --head x.obj -o " + (dir / "b").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::usage)) << r.output;
  r = run_cli("template build --head x.obj -o " + (dir / "c").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::usage)) << r.output;
  EXPECT_NE(r.output.find("--skin-landmarks"), std::string::npos) << r.output;
  r = run_cli("template build --ct " + (dir / "missing.nrrd").string() + " -o " + (dir / "d").string());
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("missing.nrrd"), std::string::npos) << r.output;
  r = run_cli("template -o x");
  EXPECT_NE(r.exit_code, 0) << r.output;
  for (const char* out : {"a", "b", "c", "d"}) EXPECT_FALSE(std::filesystem::exists(dir / out)) << out;
}

TEST(TemplateCli, ReconstructRefusesABadTemplateFileNamingIt) {
  const auto dir = test::scratch_dir("template_cli_bad_file");
  const auto garbage = dir / "garbage.cbor";
  {
    std::ofstream f(garbage);
    f << "this is not a template";
  }
  auto r = run_cli("reconstruct --template " + garbage.string() + " --picture-size 0 -o " + (dir / "a").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("garbage.cbor"), std::string::npos) << r.output;
  r = run_cli("reconstruct --template " + (dir / "none.cbor").string() + " --picture-size 0 -o " +
              (dir / "b").string());
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("none.cbor"), std::string::npos) << r.output;
  r = run_cli("reconstruct --template " + garbage.string() + " --ct phantom --landmarks auto -o " +
              (dir / "c").string());
  EXPECT_EQ(r.exit_code, code(ErrorKind::input)) << r.output;
  EXPECT_NE(r.output.find("garbage.cbor"), std::string::npos) << r.output;
  for (const char* out : {"a", "b", "c"}) EXPECT_FALSE(std::filesystem::exists(dir / out)) << out;
}
