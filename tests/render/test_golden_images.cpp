// Small renders of primitives compared with the committed pictures in tests/golden/render/. After an
// intended change of the renderer's look, regenerate them with FORENSIM_UPDATE_GOLDEN=1 and look at them.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "image/png_io.hpp"
#include "render/colour_bar.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

RenderSettings golden_settings() {
  RenderSettings settings;
  settings.width = 96;
  settings.height = 96;
  settings.samples_per_pixel = 8;
  settings.seed = 7;
  return settings;
}

// Compares with the golden picture (8-bit display values): mean absolute difference below 1.5 codes
// and at most 1% of pixels off by more than 24 codes (noise and float differences between machines).
void expect_matches_golden(const Image& picture, const std::string& name) {
  const std::filesystem::path path = test::tests_dir() / "golden/render" / (name + ".png");
  const char* update = std::getenv("FORENSIM_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    write_png(path, picture);
    GTEST_SKIP() << "updated " << path;
  }
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing: run with FORENSIM_UPDATE_GOLDEN=1";
  const Image golden = read_png(path, PngTransfer::identity);
  ASSERT_EQ(golden.width(), picture.width());
  ASSERT_EQ(golden.height(), picture.height());
  ASSERT_EQ(golden.channels(), picture.channels());
  double total = 0;
  int differing = 0;
  for (int y = 0; y < picture.height(); ++y)
    for (int x = 0; x < picture.width(); ++x) {
      double worst = 0;
      for (int c = 0; c < picture.channels(); ++c) {
        const double d = std::abs(std::round(picture.at(x, y, c) * 255.0) - golden.at(x, y, c) * 255.0);
        total += d;
        worst = std::max(worst, d);
      }
      if (worst > 24) ++differing;
    }
  const double pixels = static_cast<double>(picture.width()) * picture.height();
  const double mean = total / (pixels * picture.channels());
  EXPECT_LT(mean, 1.5) << name << ": mean absolute difference " << mean << " codes";
  EXPECT_LE(differing, 0.01 * pixels) << name << ": " << differing << " pixels differ by more than 24 codes";
}

}  // namespace

TEST(GoldenRender, ClayIcosphere) {
  Scene scene;
  scene.add(make_icosphere(Vec3::Zero(), 50, 3), SurfaceMaterial::clay());
  scene.add(make_box_mesh(Vec3(-90, -90, -75), Vec3(90, 90, -50), 1), SurfaceMaterial::clay(), "floor");
  scene.frame(ViewName::three_quarter, 1.0);
  expect_matches_golden(Renderer(scene).render(golden_settings()), "clay_icosphere");
}

TEST(GoldenRender, SkinSphereOverBoneBoxCutAway) {
  Scene scene;
  scene.add(make_icosphere(Vec3::Zero(), 50, 4), SurfaceMaterial::skin(), "flesh");
  scene.add(make_box_mesh(Vec3(-15, -15, -40), Vec3(15, 15, 40), 1), SurfaceMaterial::bone(), "bone");
  scene.cutaway = CutPlane{Vec3::Zero(), Vec3(1, -0.3, 0)};
  scene.frame(ViewName::three_quarter, 1.0);
  expect_matches_golden(Renderer(scene).render(golden_settings()), "skin_bone_cutaway");
}

TEST(GoldenRender, VertexColouredBox) {
  TriMesh box = make_box_mesh(Vec3(-40, -40, -40), Vec3(40, 40, 40), 2);
  for (const Vec3& p : box.positions)
    box.colors.push_back(Vec4f(static_cast<float>(p[0] / 80 + 0.5), static_cast<float>(p[1] / 80 + 0.5),
                               static_cast<float>(p[2] / 80 + 0.5), 1.0f));
  SurfaceMaterial m;
  m.colour_source = ColourSource::vertex_colours;
  m.base_colour = Vec3f(1, 1, 1);
  Scene scene;
  scene.add(box, m);
  scene.frame(ViewName::three_quarter, 1.0);
  expect_matches_golden(Renderer(scene).render(golden_settings()), "vertex_coloured_box");
}

TEST(GoldenRender, FieldWithOverlayOverSkull) {
  TriMesh face = make_icosphere(Vec3::Zero(), 50, 3);
  std::vector<double> depth(face.vertex_count());
  for (std::size_t i = 0; i < depth.size(); ++i) depth[i] = face.positions[i][2];
  face.vertex_fields.scalars["tissue_depth"] = depth;
  SurfaceMaterial overlay = SurfaceMaterial::field("tissue_depth", -50, 50, ColormapName::inferno);
  overlay.opacity = 0.5;
  Scene scene;
  scene.add(make_box_mesh(Vec3(-25, -25, -25), Vec3(25, 25, 25), 1), SurfaceMaterial::bone(), "skull");
  scene.add(face, overlay, "face");
  LineOverlay line;
  line.from = Vec3(0, -25, 0);
  line.to = Vec3(0, -50, 0);
  scene.lines.push_back(line);
  PointOverlay point;
  point.position = line.from;
  point.radius_px = 3;
  scene.points.push_back(point);
  scene.frame(ViewName::front, 1.0);
  expect_matches_golden(Renderer(scene).render(golden_settings()), "field_overlay_skull");
}

TEST(GoldenRender, TexturedQuad) {
  TriMesh quad;
  quad.positions = {{-40, 0, -40}, {40, 0, -40}, {40, 0, 40}, {-40, 0, 40}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  quad.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  quad.triangle_uvs = quad.triangles;
  compute_normals(quad);
  auto checker = std::make_shared<Image>(8, 8, 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      checker->set_rgba(x, y, (x + y) % 2 ? Vec4f(0.8f, 0.1f, 0.1f, 1) : Vec4f(0.9f, 0.9f, 0.85f, 1));
  checker->set_rgba(0, 0, Vec4f(0.1f, 0.8f, 0.1f, 1));  // top-left texel green: checks the v-up convention
  SurfaceMaterial m;
  m.colour_source = ColourSource::texture;
  m.base_colour = Vec3f(1, 1, 1);
  m.base_texture = checker;
  Scene scene;
  scene.add(quad, m);
  scene.camera = Camera::look_at(Vec3(0, -300, 0), Vec3::Zero(), Vec3::UnitZ(), 18);
  const Image picture = Renderer(scene).render(golden_settings());
  // Texel (0,0) is the top-left of the texture: it must land at the top-left of the quad.
  EXPECT_GT(picture.at(12, 12, 1), picture.at(12, 12, 2) + 0.1f);
  expect_matches_golden(picture, "textured_quad");
}

TEST(GoldenRender, SheetWithCaptionsAndLegend) {
  RenderSettings settings = golden_settings();
  settings.width = 64;
  settings.height = 64;
  settings.samples_per_pixel = 4;
  std::vector<SheetCell> cells;
  for (int i = 0; i < 3; ++i) {
    Scene scene;
    scene.add(make_icosphere(Vec3::Zero(), 30 + 10 * i, 2), SurfaceMaterial::skin());
    scene.frame(ViewName::front, 1.0);
    cells.push_back({Renderer(scene).render(settings), "day " + std::to_string(i)});
  }
  ColourBar bar;
  bar.title = std::string("depth");
  bar.unit = std::string("mm");
  bar.min = 0;
  bar.max = 30;
  bar.ticks = 4;
  bar.font_px = 11;
  const Image sheet = with_colour_bar(make_sheet(cells, 3, "Timeline", {}), bar);
  expect_matches_golden(sheet, "sheet_legend");
}
