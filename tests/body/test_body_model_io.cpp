#include "body/body_model_io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "body_test_meshes.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "support/test_support.hpp"
#include "tet_io/vtu_writer.hpp"

using namespace forensim;
using test::box_model;

namespace {

void replace_in_file(const std::filesystem::path& path, const std::string& from, const std::string& to) {
  std::string text = read_file(path);
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  write_file_atomic(path, text);
}

}  // namespace

TEST(BodyModelIo, RoundTripIsExact) {
  BodyModel model = box_model();
  // A CT head lying on its back: drawn feet-up in the scan's frame, gravity towards the back of the head.
  model.pose.views = "head";
  model.pose.up = -Vec3::UnitZ();
  model.pose.front = Vec3(0.6, -0.8, 0.0);
  model.pose.gravity = Vec3(-0.6, 0.8, 0.0);
  const auto folder = test::scratch_dir("body_model_io") / "box";
  write_body_model(folder, model);
  const BodyModel back = read_body_model(folder);
  EXPECT_EQ(back.volume.positions, model.volume.positions);
  EXPECT_EQ(back.volume.tets, model.volume.tets);
  EXPECT_EQ(back.volume.tet_labels, model.volume.tet_labels);
  EXPECT_EQ(back.skin.positions, model.skin.positions);
  EXPECT_EQ(back.skin.triangles, model.skin.triangles);
  EXPECT_EQ(back.part_names, model.part_names);
  EXPECT_EQ(back.skin_vertex_parts, model.skin_vertex_parts);
  EXPECT_EQ(back.tet_parts, model.tet_parts);
  EXPECT_EQ(back.tracking.boundary_face, model.tracking.boundary_face);
  EXPECT_EQ(back.tracking.face_nodes, model.tracking.face_nodes);
  EXPECT_EQ(back.tracking.weights, model.tracking.weights);
  EXPECT_EQ(back.tracking.rest_distance, model.tracking.rest_distance);
  EXPECT_EQ(back.tracking.side, model.tracking.side);
  EXPECT_EQ(back.tracking.method, model.tracking.method);
  EXPECT_EQ(back.pose.views, "head");
  EXPECT_EQ(back.pose.up, model.pose.up);
  EXPECT_EQ(back.pose.front, model.pose.front);
  EXPECT_EQ(back.pose.gravity, model.pose.gravity);
  EXPECT_TRUE(back.skin.vertex_fields.empty()) << "tracking arrays must not leak into the skin's fields";
  EXPECT_TRUE(back.volume.tet_fields.empty());
}

TEST(BodyModelIo, BadFoldersAreClearErrors) {
  const auto root = test::scratch_dir("body_model_io");
  EXPECT_THROW(read_body_model(root / "does_not_exist"), IoError);

  const auto folder = root / "bad";
  write_body_model(folder, box_model());
  replace_in_file(folder / "model.json", "\"version\": 1", "\"version\": 7");
  EXPECT_THROW(read_body_model(folder), InputError);

  write_body_model(folder, box_model());
  replace_in_file(folder / "model.json", "\"skin.vtu\"", "\"../skin.vtu\"");
  EXPECT_THROW(read_body_model(folder), InputError);

  // A skin from another model: tracking arrays missing.
  write_body_model(folder, box_model());
  write_vtu(folder / "skin.vtu", make_box_mesh(Vec3::Zero(), Vec3::Constant(1.0), 2));
  try {
    read_body_model(folder);
    FAIL() << "skin without tracking accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("skin.vtu"), std::string::npos) << e.what();
  }

  // Tracking that no longer matches the volume (a different volume written over it).
  write_body_model(folder, box_model());
  TetMesh other = make_box_tet_mesh(Vec3::Zero(), Vec3::Constant(10.0), 2, 2, 2);
  write_vtu(folder / "volume.vtu", other);
  EXPECT_THROW(read_body_model(folder), InputError);

  // A folder without a pose (written before poses were stored) reads as a limb, gravity -z.
  write_body_model(folder, box_model());
  {
    nlohmann::json json = nlohmann::json::parse(read_file(folder / "model.json"));
    json.erase("pose");
    write_file_atomic(folder / "model.json", json.dump(2));
    const BodyModel old = read_body_model(folder);
    EXPECT_EQ(old.pose.views, "arm");
    EXPECT_EQ(old.pose.gravity, -Vec3::UnitZ());
  }
  // Bad poses: unknown keys, views, non-unit and non-orthogonal vectors.
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"\"views\": \"arm\"", "\"views\": \"leg\""},
           {"\"views\": \"arm\"", "\"view\": \"arm\""},
           {"\"gravity\": [", "\"gravity\": [7, "},
           {"\"up\": [\n      0.0,\n      0.0,\n      1.0", "\"up\": [\n      0.0,\n      0.0,\n      2.0"},
           {"\"up\": [\n      0.0,\n      0.0,\n      1.0", "\"up\": [\n      0.0,\n      1.0,\n      0.0"}}) {
    write_body_model(folder, box_model());
    replace_in_file(folder / "model.json", from, to);
    EXPECT_THROW(read_body_model(folder), InputError) << to;
  }

  std::ofstream(folder / "model.json") << "{ not json";
  EXPECT_THROW(read_body_model(folder), InputError);
}
