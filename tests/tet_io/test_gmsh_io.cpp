#include "tet_io/gmsh_io.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "core/error.hpp"
#include "support/test_support.hpp"
#include "tet_io/sample_tet_mesh.hpp"

using namespace forensim;
using forensim::test::sample_tet_mesh;

TEST(GmshIo, AsciiRoundTripKeepsIndicesPositionsAndLabels) {
  const TetMesh mesh = sample_tet_mesh();
  const auto path = test::scratch_dir("msh") / "box.msh";
  write_gmsh(path, mesh);
  const TetMesh back = read_gmsh(path);
  test::expect_same_geometry(mesh, back);
  test::expect_same_fields(mesh.vertex_fields, back.vertex_fields);
  test::expect_same_fields(mesh.tet_fields, back.tet_fields);
  const std::string text = test::slurp(path);
  EXPECT_NE(text.find("3 1 \"flesh\""), std::string::npos);
  EXPECT_NE(text.find("3 2 \"bone\""), std::string::npos);
  EXPECT_NE(text.find("3 3 \"region_7\""), std::string::npos);
}

TEST(GmshIo, BinaryRoundTripKeepsIndicesPositionsAndLabels) {
  const TetMesh mesh = sample_tet_mesh(4, 3, 2);
  const auto path = test::scratch_dir("msh") / "box.msh";
  write_gmsh(path, mesh, true);
  EXPECT_EQ(test::slurp(path).rfind("$MeshFormat\n4.1 1 8\n", 0), 0u);
  const TetMesh back = read_gmsh(path);
  test::expect_same_geometry(mesh, back);
  test::expect_same_fields(mesh.vertex_fields, back.vertex_fields);
  test::expect_same_fields(mesh.tet_fields, back.tet_fields);
}

TEST(GmshIo, UnlabelledMeshReadsBackUnlabelled) {
  TetMesh mesh = sample_tet_mesh(1, 1, 1);
  mesh.tet_labels.clear();
  const auto path = test::scratch_dir("msh") / "plain.msh";
  write_gmsh(path, mesh);
  const TetMesh back = read_gmsh(path);
  test::expect_same_geometry(mesh, back);
  EXPECT_TRUE(back.tet_labels.empty());
}

// Hand-written like Gmsh's own output: sparse unordered node tags, a parametric node block, point, triangle and
// quadratic-tet elements to skip, physical groups named outside forensim's convention, a volume without one.
constexpr const char* hand_written_41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
2 5 "skin"
3 10 "muscle"
3 11 "bone"
$EndPhysicalNames
$Comments
anything here is ignored $Nodes
$EndComments
$Entities
1 0 1 3
7 1 1 1 0
3 0 0 -1 1 1 0 1 5 0
1 0 0 0 1 1 1 1 10 1 3
2 0 0 -1 1 1 1 1 11 1 3
3 0 0 0 1 1 1 0 0
$EndEntities
$Nodes
3 6 10 500
0 7 0 1
500
1 1 1
2 3 1 1
77
0.5 0.5 -1 0.25 0.75
3 1 0 4
10
20
30
40
0 0 0
1 0 0
0 1 0
0 0 1
$EndNodes
$Elements
6 7 2 120
0 7 15 1
100 500
2 3 2 1
101 10 20 77
3 1 4 2
110 10 20 30 40
105 20 30 40 500
3 2 4 1
120 10 30 40 77
3 3 4 1
2 10 20 30 500
3 1 11 1
50 10 20 30 40 500 77 10 20 30 40
$EndElements
)";

TEST(GmshIo, ReadsSparseTagsAndSkipsOtherElementTypes) {
  const auto path = test::scratch_dir("msh") / "hand.msh";
  test::spit(path, hand_written_41);
  const TetMesh mesh = read_gmsh(path);
  ASSERT_EQ(mesh.vertex_count(), 6u);  // file order: 500, 77, 10, 20, 30, 40
  EXPECT_EQ(mesh.positions[0], Vec3(1, 1, 1));
  EXPECT_EQ(mesh.positions[1], Vec3(0.5, 0.5, -1));
  EXPECT_EQ(mesh.positions[5], Vec3(0, 0, 1));
  ASSERT_EQ(mesh.tet_count(), 4u);  // ordered by element tag: 2, 105, 110, 120
  EXPECT_EQ(mesh.tets[0], (Tet{2, 3, 4, 0}));
  EXPECT_EQ(mesh.tets[1], (Tet{3, 4, 5, 0}));
  EXPECT_EQ(mesh.tets[2], (Tet{2, 3, 4, 5}));
  EXPECT_EQ(mesh.tets[3], (Tet{2, 4, 5, 1}));
  EXPECT_EQ(mesh.label(0), 3);   // volume 3 has no physical group: entity tag
  EXPECT_EQ(mesh.label(1), 10);  // "muscle": physical tag
  EXPECT_EQ(mesh.label(2), 10);
  EXPECT_EQ(mesh.label(3), tissue_bone);  // "bone"
}

TEST(GmshIo, ReadsMsh22Ascii) {
  const auto path = test::scratch_dir("msh") / "old.msh";
  test::spit(path, R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
3 2 "bone"
$EndPhysicalNames
$Nodes
5
3 0 0 0
5 1 0 0
9 0 1 0
11 0 0 1
12 1 1 1
$EndNodes
$Elements
4
1 15 2 0 1 3
2 2 2 0 4 3 5 9
7 4 2 2 1 3 5 9 11
4 4 2 0 6 5 9 11 12
$EndElements
)");
  const TetMesh mesh = read_gmsh(path);
  ASSERT_EQ(mesh.vertex_count(), 5u);
  ASSERT_EQ(mesh.tet_count(), 2u);
  EXPECT_EQ(mesh.tets[0], (Tet{1, 2, 3, 4}));  // element 4
  EXPECT_EQ(mesh.tets[1], (Tet{0, 1, 2, 3}));  // element 7
  EXPECT_EQ(mesh.label(0), 6);                 // no physical group: elementary tag
  EXPECT_EQ(mesh.label(1), tissue_bone);
}

namespace {
struct BinaryMsh {
  std::string bytes;
  template <class T>
  void put(T v) {
    char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    bytes.append(raw, sizeof(T));
  }
  void text(const std::string& s) { bytes += s; }
};
}  // namespace

TEST(GmshIo, ReadsBinaryWithSkippedBlocksAndSparseTags) {
  BinaryMsh f;
  f.text("$MeshFormat\n4.1 1 8\n");
  f.put<std::int32_t>(1);
  f.text("\n$EndMeshFormat\n$Entities\n");
  for (std::uint64_t c : {0, 0, 0, 1}) f.put(c);
  f.put<std::int32_t>(4);
  for (double d : {0.0, 0.0, 0.0, 1.0, 1.0, 1.0}) f.put(d);
  f.put<std::uint64_t>(1);
  f.put<std::int32_t>(42);
  f.put<std::uint64_t>(0);
  f.text("\n$EndEntities\n$Nodes\n");
  for (std::uint64_t c : {1, 5, 3, 900}) f.put(c);
  f.put<std::int32_t>(3);
  f.put<std::int32_t>(4);
  f.put<std::int32_t>(0);
  f.put<std::uint64_t>(5);
  for (std::uint64_t tag : {900, 3, 17, 8, 4}) f.put(tag);
  for (double d : {1., 1., 1., 0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.}) f.put(d);
  f.text("\n$EndNodes\n$Elements\n");
  for (std::uint64_t c : {2, 3, 1, 9}) f.put(c);
  f.put<std::int32_t>(2);  // triangle block, skipped
  f.put<std::int32_t>(1);
  f.put<std::int32_t>(2);
  f.put<std::uint64_t>(1);
  for (std::uint64_t v : {1, 3, 17, 8}) f.put(v);
  f.put<std::int32_t>(3);  // tet block in volume 4 (physical 42)
  f.put<std::int32_t>(4);
  f.put<std::int32_t>(4);
  f.put<std::uint64_t>(2);
  for (std::uint64_t v : {9, 17, 8, 4, 900, 5, 3, 17, 8, 4}) f.put(v);
  f.text("\n$EndElements\n");
  const auto path = test::scratch_dir("msh") / "binary.msh";
  test::spit(path, f.bytes);
  const TetMesh mesh = read_gmsh(path);
  ASSERT_EQ(mesh.vertex_count(), 5u);
  ASSERT_EQ(mesh.tet_count(), 2u);
  EXPECT_EQ(mesh.tets[0], (Tet{1, 2, 3, 4}));  // element 5
  EXPECT_EQ(mesh.tets[1], (Tet{2, 3, 4, 0}));  // element 9
  EXPECT_EQ(mesh.label(0), 42);
  EXPECT_EQ(mesh.positions[4], Vec3(0, 0, 1));
}

TEST(GmshIo, ErrorsNameFileAndLine) {
  const auto path = test::scratch_dir("msh") / "bad.msh";
  std::string text = hand_written_41;
  text.replace(text.find("0.5 0.5 -1"), 10, "0.5 nan -1");
  test::spit(path, text);
  try {
    read_gmsh(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path.string());
    EXPECT_EQ(e.location(), "line 28");  // the line of "0.5 nan -1"
    EXPECT_NE(e.problem().find("node coordinate"), std::string::npos) << e.what();
  }
}

TEST(GmshIo, MissingFileIsIoError) {
  EXPECT_THROW(read_gmsh(test::scratch_dir("msh") / "absent.msh"), IoError);
}

TEST(GmshIo, NodesWithoutTetsRoundTrip) {
  TetMesh mesh = sample_tet_mesh(1, 1, 1);
  mesh.tets.clear();
  mesh.tet_labels.clear();
  mesh.tet_fields = {};
  for (bool binary : {false, true}) {
    const auto path = test::scratch_dir("msh") / "cloud.msh";
    write_gmsh(path, mesh, binary);
    test::expect_same_geometry(mesh, read_gmsh(path));
  }
  TetMesh empty;
  const auto path = test::scratch_dir("msh") / "empty.msh";
  write_gmsh(path, empty);
  EXPECT_EQ(read_gmsh(path).vertex_count(), 0u);
}

TEST(GmshIo, WindowsLineEndingsReadTheSame) {
  std::string crlf;
  for (char c : std::string(hand_written_41)) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  const TetMesh mesh = parse_gmsh(crlf, "crlf.msh");
  const TetMesh reference = parse_gmsh(hand_written_41, "lf.msh");
  test::expect_same_geometry(reference, mesh);
}
