// Files written by Gmsh 4.8.4, TetGen 1.5.0 and VTK 9.1 (see tests/tet_io/foreign/README.md) read correctly.

#include <gtest/gtest.h>

#include <map>

#include "support/test_support.hpp"
#include "tet_io/gmsh_io.hpp"
#include "tet_io/tetgen_io.hpp"
#include "tet_io/vtu_reader.hpp"

using namespace forensim;

namespace {

std::filesystem::path foreign(const std::string& name) {
  return test::tests_dir() / "tet_io" / "foreign" / name;
}

double signed_volume(const TetMesh& m, std::size_t t) {
  const auto& p = m.positions;
  const Tet& k = m.tets[t];
  return (p[k[1]] - p[k[0]]).dot((p[k[2]] - p[k[0]]).cross(p[k[3]] - p[k[0]])) / 6.0;
}

std::map<int, double> volume_per_label(const TetMesh& m) {
  std::map<int, double> v;
  for (std::size_t t = 0; t < m.tet_count(); ++t) v[m.label(t)] += signed_volume(m, t);
  return v;
}

}  // namespace

TEST(ForeignFiles, GmshMeshesOfTwoBoxesInEveryFormat) {
  const TetMesh ascii = read_gmsh(foreign("gmsh_two_boxes_41.msh"));
  const TetMesh binary = read_gmsh(foreign("gmsh_two_boxes_41_binary.msh"));
  const TetMesh old = read_gmsh(foreign("gmsh_two_boxes_22.msh"));
  ASSERT_GT(ascii.tet_count(), 50u);
  for (std::size_t t = 0; t < ascii.tet_count(); ++t) ASSERT_GT(signed_volume(ascii, t), 0.0) << "tet " << t;
  // "bone" (physical 2) is forensim's bone label; "soft tissue" keeps its physical tag 5.
  const auto volumes = volume_per_label(ascii);
  ASSERT_EQ(volumes.size(), 2u);
  EXPECT_NEAR(volumes.at(tissue_bone), 0.4, 1e-12);
  EXPECT_NEAR(volumes.at(5), 0.6, 1e-12);
  for (const TetMesh* other : {&binary, &old}) {
    ASSERT_EQ(other->vertex_count(), ascii.vertex_count());
    ASSERT_EQ(other->tet_count(), ascii.tet_count());
    for (std::size_t t = 0; t < ascii.tet_count(); ++t) {
      ASSERT_EQ(other->tets[t], ascii.tets[t]);
      ASSERT_EQ(other->label(t), ascii.label(t));
    }
    for (std::size_t v = 0; v < ascii.vertex_count(); ++v) {
      ASSERT_LT((other->positions[v] - ascii.positions[v]).norm(), 1e-14);
    }
  }
}

TEST(ForeignFiles, TetgenDelaunayOfACube) {
  const TetMesh mesh = read_tetgen(foreign("cube_points.1"));
  EXPECT_EQ(mesh.vertex_count(), 12u);
  ASSERT_EQ(mesh.tet_count(), 30u);
  double volume = 0.0;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    ASSERT_GT(signed_volume(mesh, t), 0.0) << "tet " << t;  // TetGen orients tets as forensim does
    volume += signed_volume(mesh, t);
  }
  EXPECT_NEAR(volume, 1.0, 1e-12);
  EXPECT_EQ(mesh.positions[8], Vec3(0.5, 0.5, 0.5));  // 0-based indices kept
}

TEST(ForeignFiles, VtkWrittenVtuInEveryEncoding) {
  for (const char* name :
       {"vtk_ascii.vtu", "vtk_binary_zlib_uint32.vtu", "vtk_appended_raw.vtu", "vtk_appended_zlib.vtu"}) {
    SCOPED_TRACE(name);
    const TetMesh mesh = read_vtu(foreign(name));
    ASSERT_EQ(mesh.vertex_count(), 5u);
    ASSERT_EQ(mesh.tet_count(), 2u);
    EXPECT_EQ(mesh.tets[0], (Tet{0, 1, 2, 3}));
    EXPECT_EQ(mesh.tets[1], (Tet{1, 2, 3, 4}));
    EXPECT_EQ(mesh.positions[4], Vec3(1, 1, 1));
    EXPECT_EQ(mesh.label(0), tissue_flesh);
    EXPECT_EQ(mesh.label(1), tissue_bone);
    EXPECT_EQ(mesh.vertex_fields.scalars.at("moisture"), (std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.5}));
    EXPECT_EQ(mesh.vertex_fields.vectors.at("displacement")[3], Vec3(1.5, -3, 0.25));
    EXPECT_EQ(mesh.tet_fields.scalars.at("shrinkage"), (std::vector<double>{0.125, 0.75}));
  }
}
