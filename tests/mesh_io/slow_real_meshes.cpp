// Real meshes from /work/shared/data (scans, statues, a WebXR hand) through import and export, and
// randomly damaged files that must fail cleanly. Skips when the shared data is absent.
#include <gtest/gtest.h>

#include <spdlog/spdlog.h>

#include <random>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_topology.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "mesh_io/mesh_import.hpp"
#include "mesh_io/mesh_writer.hpp"
#include "mesh_io/ply_writer.hpp"
#include "mesh_io_test_meshes.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

void expect_plausible_mm(const TriMesh& mesh) {
  const double diagonal = bounding_box(mesh.positions).diagonal();
  EXPECT_GT(diagonal, 20.0);
  EXPECT_LT(diagonal, 5000.0);
}

}  // namespace

TEST(RealMeshes, HandClosedObj) {
  FORENSIM_REQUIRE_DATA(path, "hand-mesh/hand_closed.obj");
  const TriMesh mesh = import_mesh(path, {"m", 0.0});  // rescaled SMPL hand, ~0.94 units tall
  EXPECT_EQ(mesh.vertex_count(), 7993u);
  EXPECT_EQ(mesh.triangle_count(), 15982u);
  EXPECT_FALSE(mesh.has_uvs());
  const BoundingBox b = bounding_box(mesh.positions);
  EXPECT_NEAR(b.min[1], 0.0, 5.0);
  EXPECT_NEAR(b.max[1], 940.0, 10.0);
  expect_plausible_mm(mesh);
  const TopologyReport r = check_topology(mesh);
  EXPECT_TRUE(r.is_closed());
  EXPECT_TRUE(r.is_manifold());
}

TEST(RealMeshes, HeadBustsObj) {
  FORENSIM_REQUIRE_DATA(nefertiti_path, "head-busts/nefertiti-lowres.obj");
  const TriMesh nefertiti = import_mesh(nefertiti_path);  // already in millimetres
  EXPECT_EQ(nefertiti.vertex_count(), 35002u);
  EXPECT_EQ(nefertiti.triangle_count(), 70000u);
  EXPECT_NEAR(bounding_box(nefertiti.positions).size()[1], 494.6, 2.0);
  expect_plausible_mm(nefertiti);
  EXPECT_TRUE(check_topology(nefertiti).is_closed());

  FORENSIM_REQUIRE_DATA(demosthenes_path, "head-busts/demosthenes-low-res.obj");
  const TriMesh demosthenes = import_mesh(demosthenes_path, {"auto", 100.0});  // ~2.7 units tall
  EXPECT_EQ(demosthenes.vertex_count(), 8394u);
  EXPECT_EQ(demosthenes.triangle_count(), 16719u);
  expect_plausible_mm(demosthenes);
}

TEST(RealMeshes, LeePerrySmithGlbWeldsSeamsAndKeepsUvs) {
  FORENSIM_REQUIRE_DATA(path, "head-scan-lee-perry-smith/LeePerrySmith.glb");
  const ImportedMesh imported = import_mesh_with_textures(path, {"auto", 30.0});  // ~8.6 units -> ~26 cm
  const TriMesh& mesh = imported.mesh;
  EXPECT_EQ(mesh.triangle_count(), 17684u);
  EXPECT_LE(mesh.vertex_count(), 9279u);  // the file splits vertices at UV seams; we weld them
  EXPECT_GT(mesh.vertex_count(), 8000u);
  EXPECT_TRUE(mesh.has_uvs());
  EXPECT_TRUE(mesh.has_normals());
  expect_plausible_mm(mesh);
  for (const Vec2& uv : mesh.uvs) {
    EXPECT_GE(uv[0], -1e-6);
    EXPECT_LE(uv[0], 1.0 + 1e-6);
  }

  // Export to GLB and back: the same welded mesh, with the same UV at every triangle corner.
  const auto dir = test::scratch_dir("lee-perry-smith");
  write_mesh(dir / "head.glb", mesh);
  test::expect_same_mesh(mesh, import_mesh(dir / "head.glb"), 1e-3, true, true, false);
  write_mesh(dir / "head.ply", mesh);
  EXPECT_EQ(import_mesh(dir / "head.ply").vertex_count(), mesh.vertex_count());
}

TEST(RealMeshes, WebXrHandGlbIsInMetres) {
  FORENSIM_REQUIRE_DATA(path, "hand-webxr-uv/left.glb");
  const TriMesh mesh = import_mesh(path);  // glTF: metres -> mm
  EXPECT_EQ(mesh.triangle_count(), 2314u);
  EXPECT_LE(mesh.vertex_count(), 1360u);
  EXPECT_TRUE(mesh.has_uvs());
  const Vec3 size = bounding_box(mesh.positions).size();
  EXPECT_GT(size.maxCoeff(), 150.0);  // a hand is ~19 cm long
  EXPECT_LT(size.maxCoeff(), 300.0);
  expect_plausible_mm(mesh);
}

// Random damage (byte flips, truncation, overwritten header fields) to valid files of every format: each
// damaged file must import or throw a forensim::Error, never crash (run under ASan in CI).
TEST(DamagedFiles, NeverCrash) {
  const auto dir = test::scratch_dir("damaged");
  const TriMesh box = test::make_uv_box(Vec3(0, 0, 0), Vec3(100, 120, 140), 2);
  std::vector<std::string> names = {"box.obj", "box.ply", "box.stl", "box.glb", "box.gltf"};
  for (const std::string& name : names) write_mesh(dir / name, box);
  PlyWriteOptions ascii{PlyFormat::ascii};
  write_ply(dir / "ascii.ply", box, ascii);
  names.push_back("ascii.ply");
  std::mt19937 random(20261122);
  const spdlog::level::level_enum log_level = spdlog::get_level();
  spdlog::set_level(spdlog::level::off);  // damaged files warn about implausible sizes
  int imported = 0, rejected = 0;
  for (const std::string& name : names) {
    const std::string original = read_file(dir / name);
    for (int trial = 0; trial < 150; ++trial) {
      std::string bytes = original;
      const int kind = trial % 3;
      if (kind == 0) {
        bytes.resize(std::uniform_int_distribution<std::size_t>(0, bytes.size() - 1)(random));
      } else {
        const int flips = 1 + static_cast<int>(random() % 8);
        for (int f = 0; f < flips; ++f) {
          // Early bytes hold the headers; damage them more often.
          const std::size_t limit = (kind == 1) ? std::min<std::size_t>(bytes.size(), 256) : bytes.size();
          const std::size_t at = std::uniform_int_distribution<std::size_t>(0, limit - 1)(random);
          bytes[at] = static_cast<char>(random() & 0xFF);
        }
      }
      const std::filesystem::path damaged = dir / ("damaged_" + std::to_string(trial) + "_" + name);
      write_file_atomic(damaged, bytes);
      try {
        const TriMesh mesh = import_mesh(damaged, {"mm", 0.0});
        mesh.validate("damaged mesh");
        ++imported;
      } catch (const Error&) {
        ++rejected;
      }
      std::filesystem::remove(damaged);
    }
  }
  spdlog::set_level(log_level);
  EXPECT_GT(rejected, 0);
  RecordProperty("imported", imported);
  RecordProperty("rejected", rejected);
}
