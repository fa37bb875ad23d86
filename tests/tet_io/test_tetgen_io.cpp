#include "tet_io/tetgen_io.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "support/test_support.hpp"
#include "tet_io/sample_tet_mesh.hpp"

using namespace forensim;
using forensim::test::sample_tet_mesh;

TEST(TetgenIo, RoundTripKeepsEverything) {
  TetMesh mesh = sample_tet_mesh();
  std::vector<double> markers(mesh.vertex_count());
  for (std::size_t v = 0; v < markers.size(); ++v) markers[v] = static_cast<double>(v % 3);
  mesh.vertex_fields.scalars["boundary_marker"] = markers;
  const auto base = test::scratch_dir("tetgen") / "box";
  write_tetgen(base, mesh);
  for (const char* input : {"box", "box.node", "box.ele"}) {
    const TetMesh back = read_tetgen(base.parent_path() / input);
    test::expect_same_geometry(mesh, back);
    test::expect_same_fields(mesh.vertex_fields, back.vertex_fields);
    test::expect_same_fields(mesh.tet_fields, back.tet_fields);
  }
  // The boundary marker is TetGen's marker column, not an attribute.
  EXPECT_NE(test::slurp(base.string() + ".node").find(" 3 4 1\n"), std::string::npos);
}

TEST(TetgenIo, ReadsZeroBasedFilesWithCommentsQuadraticTetsAndUnnamedAttributes) {
  const auto dir = test::scratch_dir("tetgen");
  test::spit(dir / "t.node", R"(# TetGen-style node file
5  3  1  0   # 5 nodes, 1 attribute, no markers

0  0 0 0  0.5
1  1 0 0  1.5
2  0 1 0  2.5 # trailing comment
3  0 0 1  3.5
4  1 1 1  4.5
)");
  test::spit(dir / "t.ele", R"(2 10 1
0  0 1 2 3  0 0 0 0 0 0  -1
1  1 2 3 4  0 0 0 0 0 0  2
)");
  const TetMesh mesh = read_tetgen(dir / "t");
  ASSERT_EQ(mesh.vertex_count(), 5u);
  ASSERT_EQ(mesh.tet_count(), 2u);
  EXPECT_EQ(mesh.tets[1], (Tet{1, 2, 3, 4}));
  EXPECT_EQ(mesh.label(0), -1);
  EXPECT_EQ(mesh.label(1), 2);
  ASSERT_TRUE(mesh.vertex_fields.scalars.count("attribute_0"));
  EXPECT_EQ(mesh.vertex_fields.scalars.at("attribute_0")[2], 2.5);
}

TEST(TetgenIo, RejectsIndexOutOfRangeWithLine) {
  const auto dir = test::scratch_dir("tetgen");
  test::spit(dir / "t.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  test::spit(dir / "t.ele", "# one tet\n1 4 0\n1 1 2 3 5\n");
  try {
    read_tetgen(dir / "t.ele");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location(), "line 3");
    EXPECT_NE(e.problem().find("out of range"), std::string::npos) << e.what();
  }
}

TEST(TetgenIo, WritingToANodePathWritesThePair) {
  const TetMesh mesh = sample_tet_mesh(1, 1, 1);
  const auto dir = test::scratch_dir("tetgen");
  write_tetgen(dir / "pair.node", mesh);
  EXPECT_TRUE(std::filesystem::exists(dir / "pair.ele"));
  EXPECT_FALSE(std::filesystem::exists(dir / "pair.node.node"));
  test::expect_same_geometry(mesh, read_tetgen(dir / "pair"));
}

TEST(TetgenIo, MissingEleIsIoError) {
  const auto dir = test::scratch_dir("tetgen");
  test::spit(dir / "t.node", "1 3 0 0\n1 0 0 0\n");
  EXPECT_THROW(read_tetgen(dir / "t"), IoError);
}

TEST(TetgenIo, WindowsLineEndingsReadTheSame) {
  const TetMesh mesh = parse_tetgen("# nodes\r\n4 3 0 1\r\n1 0 0 0 5\r\n2 1 0 0 5\r\n3 0 1 0 6\r\n4 0 0 1 6\r\n",
                                    "1 4 1\r\n1 1 2 3 4 1\r\n", "crlf.node", "crlf.ele");
  ASSERT_EQ(mesh.tet_count(), 1u);
  EXPECT_EQ(mesh.label(0), tissue_bone);
  EXPECT_EQ(mesh.vertex_fields.scalars.at("boundary_marker")[2], 6.0);
}
