// The template file: a round trip keeps every number of the template exactly; malformed files are refused with
// the file and the field named.
#include "craniofacial/template_file.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "template_head_fixture.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;

namespace {

void expect_same_mesh(const TriMesh& a, const TriMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.triangle_uvs, b.triangle_uvs);
  ASSERT_EQ(a.normals.size(), b.normals.size());
  ASSERT_EQ(a.uvs.size(), b.uvs.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) ASSERT_EQ(a.positions[i], b.positions[i]) << i;
  for (std::size_t i = 0; i < a.normals.size(); ++i) ASSERT_EQ(a.normals[i], b.normals[i]) << i;
  for (std::size_t i = 0; i < a.uvs.size(); ++i) ASSERT_EQ(a.uvs[i], b.uvs[i]) << i;
}

std::string problem_of(const std::string& bytes) {
  try {
    decode_template_head(bytes, "t.cbor");
  } catch (const InputError& e) {
    return std::string(e.what());
  }
  return "";
}

}  // namespace

TEST(TemplateFile, RoundTripKeepsEveryNumber) {
  TemplateHead head = coarse_template_head();
  head.texture_png = std::string("\x89PNG\r\n\x1a\n", 8) + "rest of an image";
  const auto path = std::filesystem::temp_directory_path() / "forensim_template_roundtrip.cbor";
  write_template_head(path, head);
  const TemplateHead back = read_template_head(path);
  std::filesystem::remove(path);
  expect_same_mesh(head.skin, back.skin);
  expect_same_mesh(head.skull, back.skull);
  EXPECT_EQ(head.triangle_chart, back.triangle_chart);
  EXPECT_EQ(head.chart_names, back.chart_names);
  EXPECT_EQ(head.uv_l2_stretch, back.uv_l2_stretch);
  EXPECT_EQ(head.uv_overlap_free, back.uv_overlap_free);
  EXPECT_EQ(head.source, back.source);
  EXPECT_EQ(head.texture_png, back.texture_png);
  ASSERT_EQ(head.landmarks.size(), back.landmarks.size());
  for (std::size_t i = 0; i < head.landmarks.size(); ++i) {
    const TemplateLandmarkPair& a = head.landmarks[i];
    const TemplateLandmarkPair& b = back.landmarks[i];
    EXPECT_EQ(a.bone_name, b.bone_name);
    EXPECT_EQ(a.skin_name, b.skin_name);
    EXPECT_EQ(a.skull, b.skull);
    EXPECT_EQ(a.skull_normal, b.skull_normal);
    EXPECT_EQ(a.skin, b.skin);
    EXPECT_EQ(a.depth_mm, b.depth_mm);
    EXPECT_EQ(a.midline, b.midline);
  }
  ASSERT_EQ(head.skin_landmarks.size(), back.skin_landmarks.size());
  for (std::size_t i = 0; i < head.skin_landmarks.size(); ++i) {
    EXPECT_EQ(head.skin_landmarks[i].name, back.skin_landmarks[i].name);
    EXPECT_EQ(head.skin_landmarks[i].position, back.skin_landmarks[i].position);
  }
  ASSERT_EQ(head.muscles.size(), back.muscles.size());
  for (std::size_t i = 0; i < head.muscles.size(); ++i) {
    const MuscleLayout& a = head.muscles[i];
    const MuscleLayout& b = back.muscles[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.fibre_count, b.fibre_count);
    EXPECT_EQ(a.samples_per_fibre, b.samples_per_fibre);
    EXPECT_EQ(a.thickness_mm, b.thickness_mm);
    EXPECT_EQ(a.grid, b.grid);
  }
}

TEST(TemplateFile, MalformedFilesAreRefusedNamingTheField) {
  const std::string good = encode_template_head(coarse_template_head());
  EXPECT_NE(problem_of(good.substr(0, good.size() / 2)).find("not CBOR"), std::string::npos);
  EXPECT_NE(problem_of("").find("t.cbor"), std::string::npos);
  using nlohmann::json;
  const json base = json::from_cbor(good);
  const auto with = [&](const std::function<void(json&)>& edit) {
    json j = base;
    edit(j);
    const std::vector<std::uint8_t> c = json::to_cbor(j);
    return problem_of(std::string(c.begin(), c.end()));
  };
  EXPECT_NE(with([](json& j) { j["format"] = "something else"; }).find("format"), std::string::npos);
  EXPECT_NE(with([](json& j) { j["version"] = 99; }).find("version"), std::string::npos);
  EXPECT_NE(with([](json& j) { j["colour"] = 1; }).find("colour"), std::string::npos);
  EXPECT_NE(with([](json& j) { j.erase("skull"); }).find("skull"), std::string::npos);
  // A triangle index past the vertices.
  EXPECT_NE(with([](json& j) {
              auto& b = j["skin"]["triangles"].get_binary();
              const std::int32_t big = 1 << 30;
              std::memcpy(b.data(), &big, 4);
            }).find("skin"),
            std::string::npos);
  // A ragged array, a non-finite landmark, an unknown landmark name, a grid of the wrong size.
  EXPECT_NE(with([](json& j) { j["skull"]["positions"].get_binary().pop_back(); }).find("skull/positions"),
            std::string::npos);
  EXPECT_NE(with([](json& j) { j["landmarks"][0]["skull"][1] = "x"; }).find("landmarks/0/skull"), std::string::npos);
  EXPECT_NE(with([](json& j) { j["landmarks"][0]["bone"] = "glabellum"; }).find("glabellum"), std::string::npos);
  EXPECT_NE(with([](json& j) { j["landmarks"][1]["skin"] = j["landmarks"][0]["skin"]; }).find("twice"),
            std::string::npos);
  EXPECT_NE(with([](json& j) { j["muscles"][0]["fibres"] = 2000; }).find("muscles/0"), std::string::npos);
  EXPECT_NE(with([](json& j) { j["muscles"][0]["grid"].get_binary().resize(24); }).find("muscles/0/grid"),
            std::string::npos);
  EXPECT_NE(with([](json& j) { j["texture_png"] = json::binary({1, 2, 3}); }).find("texture_png"), std::string::npos);
  EXPECT_NE(with([](json& j) {
              j["triangle_chart"] = json::binary({0, 0, 0, 0});
            }).find("triangle_chart"),
            std::string::npos);
  EXPECT_THROW(read_template_head("/nonexistent/template.cbor"), IoError);
  EXPECT_EQ(with([](json&) {}), "");
}
