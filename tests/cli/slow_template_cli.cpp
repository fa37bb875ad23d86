// End-to-end runs of `forensim template build` and of `forensim reconstruct --template` with what it wrote: a
// template from the CT head phantom (the built-in template's own head) measures the built-in template's tissue
// depths again; a template from a textured head mesh with skin landmarks carries its texture into the
// reconstruction; a template from the real CT takes its face.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli/cli_runner.hpp"
#include "core/atomic_file.hpp"
#include "craniofacial/landmark_io.hpp"
#include "craniofacial/template_file.hpp"
#include "craniofacial/template_head.hpp"
#include "image/png_io.hpp"
#include "mesh_io/obj_writer.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::run_cli;

namespace {

nlohmann::json run_record(const std::filesystem::path& dir) {
  return nlohmann::json::parse(read_file(dir / "run.json"));
}

}  // namespace

TEST(SlowTemplateCli, TemplateFromTheCtPhantomMeasuresTheBuiltInDepthsAgain) {
  const auto dir = test::scratch_dir("template_slow_phantom");
  auto r = run_cli("template build --ct phantom --detail coarse --picture-size 96 -o " + (dir / "t").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"template.cbor", "template.glb", "template.png", "template_skull_landmarks.mrk.json",
                        "template_skin_landmarks.mrk.json", "run.json"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "t" / f)) << f;
  }
  const TemplateHead head = read_template_head(dir / "t" / "template.cbor");
  EXPECT_EQ(head.muscles.size(), 24u);
  const nlohmann::json facts = run_record(dir / "t")["facts"];
  // The phantom's CT is the built-in template's own head: nearly every vertex lands on its skin, and the depths
  // measured along the CT skull's normals are the built-in template's for most pairs.
  const auto conformed = facts["build"]["vertices_conformed"].get<double>();
  EXPECT_GT(conformed, 0.9 * facts["template"]["skin_vertices"].get<double>());
  std::size_t close = 0, total = 0;
  for (const auto& p : facts["pairs"]) {
    ++total;
    const double built = p["depth_mm"].get<double>(), own = p["built_in_depth_mm"].get<double>();
    if (std::abs(built - own) <= 0.2 * own + 1.5) ++close;
  }
  EXPECT_GE(close, total * 3 / 4) << close << " of " << total;
  // The reconstruction takes the file in place of the built-in template.
  r = run_cli("reconstruct --template " + (dir / "t" / "template.cbor").string() +
              " --texture-size 64 --picture-size 0 --expressions none -o " + (dir / "r").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json provenance = nlohmann::json::parse(read_file(dir / "r" / "provenance.json"));
  EXPECT_NE(provenance["template"]["source"].get<std::string>().find("CT"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "r" / "head.glb"));
}

TEST(SlowTemplateCli, TemplateFromATexturedHeadMeshCarriesItsTextureIntoTheReconstruction) {
  const auto dir = test::scratch_dir("template_slow_head");
  // A head mesh with UVs, a texture and skin landmarks: the coarse template's skin, 6 % larger, with a map
  // whose red shows u.
  TemplateHead base = make_template_head(template_head_options("coarse"));
  TriMesh head = base.skin;
  for (Vec3& p : head.positions) p *= 1.06;
  Image texture(128, 128, 3);
  for (int y = 0; y < 128; ++y) {
    for (int x = 0; x < 128; ++x) {
      texture.at(x, y, 0) = (x + 0.5f) / 128.0f;
      texture.at(x, y, 1) = 0.3f;
      texture.at(x, y, 2) = 0.2f;
    }
  }
  write_png(dir / "head.png", texture);
  head.material.base_color_texture = "head.png";
  write_obj(dir / "head.obj", head);
  LandmarkSet skin("head skin");
  for (const TemplateLandmarkPair& p : base.landmarks)
    skin.add({p.skin_name, 1.06 * p.skin, LandmarkSource::imported, 1.0});
  write_landmarks(dir / "skin.mrk.json", skin);
  auto r = run_cli("template build --head " + (dir / "head.obj").string() + " --unit mm --texture " +
                   (dir / "head.png").string() + " --skin-landmarks " + (dir / "skin.mrk.json").string() +
                   " --detail coarse --texture-size 128 --picture-size 0 -o " + (dir / "t").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const TemplateHead built = read_template_head(dir / "t" / "template.cbor");
  ASSERT_FALSE(built.texture_png.empty());
  const nlohmann::json facts = run_record(dir / "t")["facts"];
  EXPECT_TRUE(facts["build"]["texture_baked"].get<bool>());
  EXPECT_EQ(facts["build"]["pairs_from_skin"].size(), base.landmarks.size());
  // The reconstruction's head wears the baked texture (no procedural maps, no normal map).
  r = run_cli("reconstruct --template " + (dir / "t" / "template.cbor").string() +
              " --texture-size 64 --picture-size 0 --expressions none -o " + (dir / "r").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Image worn = read_png(dir / "r" / "head_epidermis.png");
  const Image baked = decode_png(built.texture_png, "baked");
  ASSERT_EQ(worn.width(), baked.width());
  EXPECT_FALSE(std::filesystem::exists(dir / "r" / "head_normal.png"));
  double diff = 0.0;
  for (int y = 0; y < worn.height(); y += 7) {
    for (int x = 0; x < worn.width(); x += 7)
      diff = std::max(diff, double(std::abs(worn.at(x, y, 0) - baked.at(x, y, 0))));
  }
  EXPECT_LT(diff, 0.01);
}

TEST(SlowTemplateCli, TemplateFromTheHeadsqCtTakesItsFace) {
  FORENSIM_REQUIRE_DATA(ct, "ct-head-headsq/quarter.nhdr");
  const auto dir = test::scratch_dir("template_slow_headsq");
  auto r =
      run_cli("template build --ct " + ct.string() + " --detail coarse --picture-size 0 -o " + (dir / "t").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::printf("%s\n", r.output.c_str());
  const nlohmann::json facts = run_record(dir / "t")["facts"];
  // The scanned face (about half the head: the vault above the orbits and the back of the neck are not in the
  // CT) lies on the CT's skin; the vault follows the completed skull at the template's own depths.
  const double conformed = facts["build"]["vertices_conformed"].get<double>();
  EXPECT_GT(conformed, 0.35 * facts["template"]["skin_vertices"].get<double>());
  EXPECT_GE(facts["build"]["pairs_from_skull"].size(), 20u);
  EXPECT_GE(facts["build"]["pairs_unscanned"].size(), 1u);
  EXPECT_LT(facts["build"]["flipped_triangles"].get<int>(), 200);
}

TEST(SlowTemplateCli, TheBuiltInTemplateThroughItsFileReconstructsTheSameHead) {
  const auto dir = test::scratch_dir("template_slow_builtin");
  auto r = run_cli("template build --builtin --detail coarse -o " + (dir / "t").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string common = " --texture-size 0 --picture-size 0 --expressions none -o ";
  r = run_cli("reconstruct --ct phantom --landmarks auto --template " + (dir / "t" / "template.cbor").string() +
              " --template-detail coarse" + common + (dir / "file").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("reconstruct --ct phantom --landmarks auto --template-detail coarse" + common + (dir / "built").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The file holds the template exactly: the same landmarks, the same skin.
  EXPECT_EQ(read_file(dir / "file" / "skin_landmarks.mrk.json"), read_file(dir / "built" / "skin_landmarks.mrk.json"));
  EXPECT_EQ(read_file(dir / "file" / "head.obj"), read_file(dir / "built" / "head.obj"));
}
