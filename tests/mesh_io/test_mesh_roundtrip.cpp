// Round trips: every writer's output read back through import_mesh (Assimp) must give the same welded
// mesh, with UV seams, normals and colours preserved where the format carries them.
#include <gtest/gtest.h>

#include <fstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "mesh_io/mesh_import.hpp"
#include "mesh_io/mesh_writer.hpp"
#include "mesh_io/obj_writer.hpp"
#include "mesh_io/ply_writer.hpp"
#include "mesh_io/uv_seam_split.hpp"
#include "mesh_io_test_meshes.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using forensim::test::expect_same_mesh;
using forensim::test::make_uv_box;

namespace {
// A head-sized box, so the plausibility warning stays quiet; coordinates exactly representable as floats.
TriMesh test_box() {
  return make_uv_box(Vec3(-80.0, -100.0, -90.0), Vec3(80.0, 140.0, 110.0), 2);
}
}  // namespace

TEST(UvSeamSplit, BoxSplitsIntoOneVertexPerFaceCorner) {
  const TriMesh box = test_box();  // n = 2: 26 welded vertices, 6 faces of 3 x 3 UV grid points
  const SeamSplitMesh split = split_uv_seams(box);
  EXPECT_EQ(box.vertex_count(), 26u);
  EXPECT_EQ(split.source_vertex.size(), 6u * 9u);
  for (std::size_t f = 0; f < box.triangle_count(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index s = split.triangles[f][c];
      EXPECT_EQ(split.source_vertex[s], box.triangles[f][c]);
      EXPECT_EQ(split.uvs[s], box.uvs[box.triangle_uvs[f][c]]);
    }
  }
}

TEST(MeshRoundTrip, ObjKeepsPositionsSeamUvsNormalsColorsAndMaterial) {
  const auto dir = test::scratch_dir("obj");
  TriMesh box = test_box();
  write_file_atomic(dir / "skin.png", test::tiny_png());
  box.material.base_color_texture = (dir / "skin.png").string();
  write_mesh(dir / "box.obj", box);
  ASSERT_TRUE(std::filesystem::exists(dir / "box.mtl"));
  const TriMesh back = import_mesh(dir / "box.obj");
  expect_same_mesh(box, back, 1e-9, true, true, true);
  EXPECT_EQ(std::filesystem::path(back.material.base_color_texture), dir / "skin.png");
  EXPECT_NEAR(back.material.base_color[0], 0.8f, 1e-6f);
  EXPECT_NEAR(back.material.base_color[2], 0.5f, 1e-6f);
}

TEST(MeshRoundTrip, ObjWithoutUvsOrNormals) {
  const auto dir = test::scratch_dir("obj-plain");
  TriMesh box = make_box_mesh(Vec3(0, 0, 0), Vec3(100, 50, 30), 1);
  box.normals.clear();
  write_mesh(dir / "plain.obj", box);
  const TriMesh back = import_mesh(dir / "plain.obj");
  expect_same_mesh(box, back, 1e-9, false, false, false);
  EXPECT_FALSE(back.has_normals());
}

TEST(MeshRoundTrip, BinaryPlyMergesSeamSplitVerticesBack) {
  const auto dir = test::scratch_dir("ply");
  const TriMesh box = test_box();
  write_mesh(dir / "box.ply", box);
  const std::string bytes = read_file(dir / "box.ply");
  ASSERT_NE(bytes.find("binary_little_endian"), std::string::npos);
  ASSERT_NE(bytes.find("element vertex 54\n"), std::string::npos);  // split at the seams in the file
  const TriMesh back = import_mesh(dir / "box.ply");
  expect_same_mesh(box, back, 1e-4, true, true, true);  // welded back to 26 vertices
}

TEST(MeshRoundTrip, AsciiPly) {
  const auto dir = test::scratch_dir("ply-ascii");
  const TriMesh box = test_box();
  write_ply(dir / "box.ply", box, PlyWriteOptions{PlyFormat::ascii});
  ASSERT_NE(read_file(dir / "box.ply").find("format ascii 1.0"), std::string::npos);
  expect_same_mesh(box, import_mesh(dir / "box.ply"), 1e-4, true, true, true);
}

TEST(MeshRoundTrip, BinaryStlKeepsPositionsAndTriangles) {
  const auto dir = test::scratch_dir("stl");
  const TriMesh box = test_box();
  write_mesh(dir / "box.stl", box);
  EXPECT_EQ(std::filesystem::file_size(dir / "box.stl"), 84u + 50u * box.triangle_count());
  expect_same_mesh(box, import_mesh(dir / "box.stl"), 1e-4, false, false, false);
}

TEST(MeshRoundTrip, GlbComesBackInMillimetresWithSeamsNormalsColorsAndEmbeddedTexture) {
  const auto dir = test::scratch_dir("glb");
  GltfMeshNode node;
  node.name = "box";
  node.mesh = test_box();
  node.textures.base_color_png = test::tiny_png();
  GltfScene scene;
  scene.nodes.push_back(node);
  write_gltf(dir / "box.glb", scene);
  const ImportedMesh back = import_mesh_with_textures(dir / "box.glb");
  EXPECT_DOUBLE_EQ(back.mm_per_unit, 1000.0);
  expect_same_mesh(node.mesh, back.mesh, 1e-4, true, true, true);
  ASSERT_EQ(back.textures.size(), 1u);
  EXPECT_EQ(back.textures[0].role, "base_color");
  EXPECT_EQ(back.textures[0].bytes, test::tiny_png());
  EXPECT_NEAR(back.mesh.material.roughness, 0.7f, 1e-6f);
  EXPECT_NEAR(back.mesh.material.base_color[1], 0.6f, 1e-6f);
}

TEST(MeshRoundTrip, GlbTextureRolesAndMaterialFilesAreEmbedded) {
  const auto dir = test::scratch_dir("glb-textures");
  // Textures named by the material (as import_mesh returns them for OBJ) are embedded from their files.
  TriMesh box = test_box();
  write_file_atomic(dir / "albedo.png", test::tiny_png());
  write_file_atomic(dir / "normal.png", test::tiny_png());
  box.material.base_color_texture = (dir / "albedo.png").string();
  box.material.normal_texture = "normal.png";                       // relative to the output's folder
  box.material.roughness_texture = (dir / "missing.png").string();  // absent: warned about, not embedded
  write_mesh(dir / "box.glb", box);
  const ImportedMesh back = import_mesh_with_textures(dir / "box.glb");
  std::vector<std::string> roles;
  for (const EmbeddedTexture& t : back.textures) {
    roles.push_back(t.role);
    EXPECT_EQ(t.bytes, test::tiny_png());
    EXPECT_EQ(t.format, "png");
  }
  EXPECT_EQ(roles, (std::vector<std::string>{"base_color", "normal"}));
  EXPECT_TRUE(back.mesh.material.base_color_texture.empty());  // embedded: bytes instead of a path

  // All three glTF slots written from bytes come back with their roles.
  GltfMeshNode node;
  node.name = "box";
  node.mesh = test_box();
  node.textures = {test::tiny_png(), test::tiny_png(), test::tiny_png()};
  GltfScene scene;
  scene.nodes.push_back(node);
  write_gltf(dir / "three.glb", scene);
  roles.clear();
  for (const EmbeddedTexture& t : import_mesh_with_textures(dir / "three.glb").textures) roles.push_back(t.role);
  EXPECT_EQ(roles, (std::vector<std::string>{"base_color", "normal", "roughness"}));
}

TEST(MeshRoundTrip, MeshesWithAndWithoutUvsMergeWithPlaceholderUvs) {
  const auto dir = test::scratch_dir("glb-mixed-uvs");
  GltfScene scene;
  GltfMeshNode plain, mapped;
  plain.name = "plain";
  plain.mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(50, 50, 50), 1);
  mapped.name = "mapped";
  mapped.mesh = make_uv_box(Vec3(100, 0, 0), Vec3(150, 50, 50), 1);
  scene.nodes = {plain, mapped};
  write_gltf(dir / "mixed.glb", scene);
  const TriMesh back = import_mesh(dir / "mixed.glb");
  ASSERT_TRUE(back.has_uvs());
  ASSERT_EQ(back.triangle_count(), 24u);
  for (std::size_t f = 0; f < back.triangle_count(); ++f) {
    const bool in_plain_box = back.positions[back.triangles[f][0]][0] < 75.0;
    for (int c = 0; c < 3; ++c) {
      const Vec2& uv = back.uvs[back.triangle_uvs[f][c]];
      if (in_plain_box)
        EXPECT_EQ(uv, Vec2::Zero()) << "triangle " << f;
      else
        EXPECT_GT(uv.norm(), 0.0) << "triangle " << f;
    }
  }
}

TEST(MeshRoundTrip, GltfJsonWithEmbeddedBuffer) {
  const auto dir = test::scratch_dir("gltf");
  const TriMesh box = test_box();
  write_mesh(dir / "box.gltf", box);
  EXPECT_NE(read_file(dir / "box.gltf").find("data:application/octet-stream;base64,"), std::string::npos);
  expect_same_mesh(box, import_mesh(dir / "box.gltf"), 1e-4, true, true, true);
}

TEST(MeshRoundTrip, NodeTranslationAndRotationAreApplied) {
  const auto dir = test::scratch_dir("glb-node");
  GltfMeshNode node;
  node.name = "moved";
  node.mesh = test_box();
  node.translation = Vec3(10.0, -20.0, 30.0);
  node.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * EIGEN_PI, Vec3::UnitZ()));
  GltfScene scene;
  scene.nodes.push_back(node);
  write_gltf(dir / "moved.glb", scene);
  TriMesh expected = node.mesh;
  for (Vec3& p : expected.positions) p = node.rotation * p + node.translation;
  for (Vec3& n : expected.normals) n = node.rotation * n;
  expect_same_mesh(expected, import_mesh(dir / "moved.glb"), 1e-3, true, true, false);
}

TEST(MeshRoundTrip, SeveralMeshesMergeIntoOneWeldedMesh) {
  const auto dir = test::scratch_dir("glb-two");
  GltfScene scene;
  GltfMeshNode a, b;
  a.name = "left";
  a.mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(50, 50, 50), 1);
  b.name = "right";
  b.mesh = make_box_mesh(Vec3(100, 0, 0), Vec3(150, 50, 50), 1);
  scene.nodes = {a, b};
  write_gltf(dir / "two.glb", scene);
  const TriMesh back = import_mesh(dir / "two.glb");
  EXPECT_EQ(back.vertex_count(), 16u);
  EXPECT_EQ(back.triangle_count(), 24u);
}

TEST(MeshWriter, UnknownExtensionIsAnInputError) {
  const auto dir = test::scratch_dir("unknown");
  EXPECT_THROW(write_mesh(dir / "box.xyz", test_box()), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "box.xyz"));
}

TEST(MeshWriter, InvalidMeshIsRejectedAndNothingIsWritten) {
  const auto dir = test::scratch_dir("invalid");
  TriMesh box = test_box();
  box.triangles[3][1] = 999;
  for (const char* name : {"bad.obj", "bad.ply", "bad.stl", "bad.glb"}) {
    EXPECT_THROW(write_mesh(dir / name, box), InputError) << name;
    EXPECT_FALSE(std::filesystem::exists(dir / name)) << name;
  }
}
