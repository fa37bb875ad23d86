#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "body/body_model_io.hpp"
#include "cli/cli_runner.hpp"
#include "core/atomic_file.hpp"
#include "geometry/mesh_measures.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

namespace {
// A closed unit-cube OBJ (mm), 12 triangles.
void write_cube_obj(const std::filesystem::path& path, double size) {
  std::ofstream out(path);
  const double s = size;
  out << "v 0 0 0\nv " << s << " 0 0\nv " << s << " " << s << " 0\nv 0 " << s << " 0\n"
      << "v 0 0 " << s << "\nv " << s << " 0 " << s << "\nv " << s << " " << s << " " << s << "\nv 0 " << s << " " << s
      << "\n"
      << "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
}

// Width and height from a PNG's IHDR chunk.
std::pair<int, int> png_size(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  auto be32 = [&](std::size_t o) {
    return (static_cast<unsigned char>(bytes[o]) << 24) | (static_cast<unsigned char>(bytes[o + 1]) << 16) |
           (static_cast<unsigned char>(bytes[o + 2]) << 8) | static_cast<unsigned char>(bytes[o + 3]);
  };
  if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0) return {0, 0};
  return {be32(16), be32(20)};
}
}  // namespace

TEST(Cli, VersionAndHelp) {
  const auto version = run_cli("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_NE(version.output.find("forensim 0."), std::string::npos) << version.output;
  const auto help = run_cli("--help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* command :
       {"info", "convert", "isosurface", "render", "phantom", "tetrahedralize", "mummify", "wound", "demo"}) {
    EXPECT_NE(help.output.find(command), std::string::npos) << command;
  }
}

// run_cli_timed runs the command line in a forked copy of the test process (cli_runner.hpp): the same exit
// code and output as the executable; the executable only where this process already runs other threads
// (tests before this one in the same process), never when the test runs alone, as CTest runs it.
TEST(CliRunner, ForkedCommandLineMatchesTheExecutable) {
  const auto dir = test::scratch_dir("cli_runner");
  const std::string cube = (dir / "cube.obj").string();
  write_cube_obj(cube, 10.0);
  write_file_atomic(dir / "garbage.obj", "v 1 2\nf 1 2 9\n");
  const std::vector<std::vector<std::string>> runs = {{"--version"},
                                                      {"info", cube},
                                                      {"info", (dir / "garbage.obj").string()},
                                                      {"info", (dir / "missing.obj").string()},
                                                      {"info", "--no-such-option", cube},
                                                      {"convert", cube, (dir / "cube.stl").string()}};
  // The same words forked and executed; only the times a command reports ("(0.05 s)") may differ.
  const std::regex seconds(R"(\([0-9.]+ s\))");
  for (const auto& arguments : runs) {
    std::string line;
    for (const auto& a : arguments) line += (line.empty() ? "" : " ") + a;
    const auto forked = test::run_cli_timed(arguments, 120.0);
    if (::testing::UnitTest::GetInstance()->test_to_run_count() == 1) {
      EXPECT_TRUE(forked.in_process) << line << ": run alone, this test's process ran the executable";
    } else if (!forked.in_process) {
      EXPECT_GT(test::thread_count(), 1) << line << ": a single-threaded test process ran the executable";
    }
    const auto executed = run_cli(line);
    EXPECT_EQ(forked.signal, 0) << line;
    EXPECT_EQ(forked.exit_code, executed.exit_code) << line;
    EXPECT_EQ(std::regex_replace(forked.output, seconds, "(s)"), std::regex_replace(executed.output, seconds, "(s)"))
        << line;
  }
}

TEST(Cli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run_cli("no-such-command").exit_code, 2);
  EXPECT_EQ(run_cli("").exit_code, 2);
  EXPECT_EQ(run_cli("isosurface -o x.ply").exit_code, 2);  // --iso missing
  EXPECT_EQ(run_cli("render --size 5 a.obj -o a.png").exit_code, 2);
}

TEST(Cli, MissingFileIsAnIoErrorNamingThePath) {
  const auto result = run_cli("info /nonexistent/skull.obj");
  EXPECT_EQ(result.exit_code, 5);
  EXPECT_NE(result.output.find("/nonexistent/skull.obj"), std::string::npos) << result.output;
}

TEST(Cli, GarbageMeshIsAnInputErrorAndWritesNothing) {
  const auto dir = test::scratch_dir("cli");
  write_file_atomic(dir / "garbage.ply",
                    std::string("ply\nformat ascii 1.0\nelement vertex 99999999999\nend_header\n1 2"));
  const auto result = run_cli("convert " + (dir / "garbage.ply").string() + " " + (dir / "out.obj").string());
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("garbage.ply"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.obj"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);  // no temporary left behind
}

TEST(Cli, ConvertRoundTripKeepsTheMesh) {
  const auto dir = test::scratch_dir("cli");
  write_cube_obj(dir / "cube.obj", 20.0);
  ASSERT_EQ(run_cli("convert " + (dir / "cube.obj").string() + " " + (dir / "cube.ply").string()).exit_code, 0);
  const auto info = run_cli("info --json " + (dir / "cube.ply").string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  const auto json = nlohmann::json::parse(info.output);
  EXPECT_EQ(json["triangles"], 12);
  EXPECT_EQ(json["closed"], true);
  EXPECT_NEAR(json["enclosed_volume_mm3"].get<double>(), 8000.0, 1e-3);
}

TEST(Cli, RenderWritesAPictureOfTheRequestedSize) {
  const auto dir = test::scratch_dir("cli");
  write_cube_obj(dir / "cube.obj", 20.0);
  const auto result = run_cli("render " + (dir / "cube.obj").string() + " -o " + (dir / "cube.png").string() +
                              " --size 64 --samples 1");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(png_size(dir / "cube.png"), std::make_pair(64, 64));
}

TEST(Cli, IsosurfaceOfThePhantomIsClosed) {
  const auto dir = test::scratch_dir("cli");
  const auto result = run_cli("isosurface --phantom-voxel 6 --iso 500 -o " + (dir / "skin.ply").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("closed, manifold, oriented"), std::string::npos) << result.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "skin.ply"));
}

TEST(Cli, TetrahedralizeWritesTetsModelAndPicture) {
  const auto dir = test::scratch_dir("cli_tet");
  std::filesystem::remove_all(dir / "model");
  write_cube_obj(dir / "cube.obj", 30.0);
  const auto result = run_cli("tetrahedralize --skin " + (dir / "cube.obj").string() +
                              " --edge 10 --surface-distance 0.1 --skin-triangles 400 --picture-size 96" + " -o " +
                              (dir / "cube.vtu").string() + " --model " + (dir / "model").string() + " --render " +
                              (dir / "cube.png").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("radius-edge ratio"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("tracking:"), std::string::npos) << result.output;
  const std::string vtu = read_file(dir / "cube.vtu");
  EXPECT_NE(vtu.find("Name=\"min_dihedral_deg\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"label\""), std::string::npos);
  const auto model = nlohmann::json::parse(read_file(dir / "model" / "model.json"));
  EXPECT_EQ(model["format"], "forensim body model");
  EXPECT_GT(model["counts"]["skin_vertices"].get<int>(), 150);
  EXPECT_TRUE(std::filesystem::exists(dir / "model" / "skin.vtu"));
  EXPECT_GT(png_size(dir / "cube.png").first, 3 * 96) << "three pictures side by side";
}

// A scan without bones: its inner offset surface is the bone; the model stores the given pose, and forensim mummify
// takes its gravity from it (livor mortis and the ground) unless the job gives one.
TEST(Cli, TetrahedralizeStoresThePoseAndAnOffsetBoneThatMummifyUses) {
  const auto dir = test::scratch_dir("cli_tet_pose");
  for (const char* f : {"model", "run", "run_own_gravity"}) std::filesystem::remove_all(dir / f);
  write_cube_obj(dir / "cube.obj", 60.0);
  const auto result = run_cli(
      "tetrahedralize --skin " + (dir / "cube.obj").string() +
      " --edge 10 --surface-distance 0.1 --no-perturb --skin-triangles 300 --bone-offset 10 --up 0 1 0 --front 0 0 1"
      " --gravity 1 0 0 --model " +
      (dir / "model").string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("inner offset surface 10.0 mm deep"), std::string::npos) << result.output;
  const BodyModel model = read_body_model(dir / "model");
  EXPECT_EQ(model.pose.views, "head");
  EXPECT_EQ(model.pose.up, Vec3::UnitY());
  EXPECT_EQ(model.pose.front, Vec3::UnitZ());
  EXPECT_EQ(model.pose.gravity, Vec3::UnitX());
  // The bone is the 40 mm cube 10 mm inside (its level set rounds the edges a little).
  const double bone = tet_mesh_volume(model.volume, tissue_bone);
  EXPECT_NEAR(bone, 40.0 * 40.0 * 40.0, 0.12 * 40.0 * 40.0 * 40.0);

  const std::string common = " --days 0.5 --frames 1 --step-hours 12 --no-pictures --map-size 0";
  auto r = run_cli("mummify --model " + (dir / "model").string() + common + " -o " + (dir / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto record = nlohmann::json::parse(read_file(dir / "run" / "run.json"));
  EXPECT_EQ(record["job"]["skin"]["gravity"], nlohmann::json::array({1.0, 0.0, 0.0})) << record["job"].dump();
  r = run_cli("mummify --model " + (dir / "model").string() + common + " --gravity 0 0 -2 -o " +
              (dir / "run_own_gravity").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto own = nlohmann::json::parse(read_file(dir / "run_own_gravity" / "run.json"));
  EXPECT_EQ(own["job"]["skin"]["gravity"], nlohmann::json::array({0.0, 0.0, -1.0})) << own["job"].dump();

  // Bad poses are usage errors, and phantoms have their own.
  EXPECT_EQ(run_cli("tetrahedralize --skin " + (dir / "cube.obj").string() + " --edge 8 --up 0 1 0").exit_code, 2);
  EXPECT_EQ(
      run_cli("tetrahedralize --skin " + (dir / "cube.obj").string() + " --edge 8 --up 0 1 0 --front 0 1 0").exit_code,
      2);
  EXPECT_EQ(run_cli("tetrahedralize --phantom arm --edge 20 --gravity 0 0 -1").exit_code, 2);
}

TEST(Cli, TetrahedralizeRejectsBadInputWithoutWriting) {
  const auto dir = test::scratch_dir("cli_tet");
  {
    std::ofstream out(dir / "flat.obj");
    out << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  std::filesystem::remove(dir / "flat.vtu");
  const auto open =
      run_cli("tetrahedralize --skin " + (dir / "flat.obj").string() + " --edge 1 -o " + (dir / "flat.vtu").string());
  EXPECT_EQ(open.exit_code, 3) << open.output;
  EXPECT_NE(open.output.find("skin surface"), std::string::npos) << open.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "flat.vtu"));
  const auto both = run_cli("tetrahedralize --phantom arm --size paper --edge 5");
  EXPECT_EQ(both.exit_code, 2) << both.output;
  const auto size = run_cli("tetrahedralize --phantom arm --size huge");
  EXPECT_EQ(size.exit_code, 3) << size.output;
  EXPECT_NE(size.output.find("huge"), std::string::npos) << size.output;
}

// Two 3 mm cubes sharing an edge (non-manifold there): the mesher's manifold criterion never converges at the
// shared edge, so tetrahedralize must end with an input error, not run on.
TEST(Cli, TetrahedralizeOfCubesSharingAnEdgeEndsWithAnError) {
  const auto dir = test::scratch_dir("cli_two_cubes");
  std::string obj;
  int base = 0;
  for (double x0 : {0.0, 3.0}) {
    const double y0 = x0;  // the second cube sits diagonally: the cubes share the edge x = y = 3
    for (int i = 0; i < 8; ++i) {
      obj += "v " + std::to_string(x0 + 3.0 * (i & 1)) + " " + std::to_string(y0 + 3.0 * ((i >> 1) & 1)) + " " +
             std::to_string(3.0 * ((i >> 2) & 1)) + "\n";
    }
    // Outward quads of the cube with corners numbered by their bits (x = 1, y = 2, z = 4).
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      obj += "f " + std::to_string(base + q[0] + 1) + " " + std::to_string(base + q[1] + 1) + " " +
             std::to_string(base + q[2] + 1) + " " + std::to_string(base + q[3] + 1) + "\n";
    }
    base += 8;
  }
  write_file_atomic(dir / "two_cubes.obj", obj);
  const auto out = dir / "two_cubes.vtu";
  std::filesystem::remove(out);
  const auto result = run_cli("tetrahedralize --skin " + (dir / "two_cubes.obj").string() +
                              " --nodes 2000 --time-limit 20 -o " + out.string());
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("skin surface"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A demo stage that fails (here on a corrupt CT in the data folder) is marked failed in the report and the run
// record, the other stages still run, and the demo exits with the stage's error code naming it.
TEST(Cli, DemoReportsAFailedStageRunsTheRestAndExitsNonZero) {
  const auto dir = test::scratch_dir("cli_demo_fail");
  const auto data = dir / "data";
  std::filesystem::create_directories(data / "ct-head-headsq");
  write_file_atomic(data / "ct-head-headsq" / "quarter.nhdr", std::string("NRRD0004\ngarbage\n"));
  const auto out = dir / "out";
  const auto result = run_cli("demo --data " + data.string() + " -o " + out.string() +
                              " --only 'real CT,phantom forearm-uv' --picture-size 96 --samples 1 --uv-resolution 128");
  EXPECT_EQ(result.exit_code, 3) << result.output;
  EXPECT_NE(result.output.find("1 of 2 stages failed: 'real CT'"), std::string::npos) << result.output;
  const std::string html = read_file(out / "report.html");
  EXPECT_NE(html.find("1 of 2 stages FAILED"), std::string::npos);
  EXPECT_NE(html.find("quarter.nhdr"), std::string::npos);
  const auto record = nlohmann::json::parse(read_file(out / "run.json"));
  ASSERT_EQ(record["facts"]["stages"]["failed"].size(), 1u);
  EXPECT_EQ(record["facts"]["stages"]["failed"][0]["stage"], "real CT");
  // The stage after the failed one ran.
  EXPECT_TRUE(record["facts"]["forearm_uv"]["overlap_free"].get<bool>());
  EXPECT_EQ(run_cli("demo --only 'no such stage' -o " + (dir / "x").string()).exit_code, 2);
}
