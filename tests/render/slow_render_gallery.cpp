// End-to-end pictures of the kinds forensim's reports show (skin over bone with a cut-away, a face
// overlay over its skull, a false-colour field with legend, a timeline sheet, a turntable). They are
// written to $FORENSIM_GALLERY_DIR (or a scratch folder) for people to look at; the assertions check
// only that each picture has content.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "image/png_io.hpp"
#include "render/colour_bar.hpp"
#include "render/quick_render.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

std::filesystem::path gallery_dir() {
  if (const char* dir = std::getenv("FORENSIM_GALLERY_DIR")) {
    std::filesystem::create_directories(dir);
    return dir;
  }
  return test::scratch_dir("gallery");
}

// A limb-like shape: an icosphere stretched along Z.
TriMesh limb(double length, double radius, int subdivisions) {
  TriMesh m = make_icosphere(Vec3::Zero(), 1.0, subdivisions);
  for (Vec3& p : m.positions) p = Vec3(p[0] * radius, p[1] * radius, p[2] * 0.5 * length);
  compute_normals(m);
  return m;
}

double spread(const Image& image) {
  double lo = 1, hi = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      lo = std::min<double>(lo, image.at(x, y, 1));
      hi = std::max<double>(hi, image.at(x, y, 1));
    }
  return hi - lo;
}

}  // namespace

TEST(RenderGallery, ArmWithBoneCutAway) {
  Scene scene;
  auto skin = std::make_shared<const TriMesh>(limb(260, 45, 5));
  auto bone = std::make_shared<const TriMesh>(limb(240, 14, 4));
  scene.add(skin, SurfaceMaterial::skin(), "skin");
  scene.add(bone, SurfaceMaterial::bone(), "bone");
  scene.cutaway = CutPlane{Vec3(0, 0, 0), Vec3(1, 0, 0)};
  RenderSettings settings;
  settings.width = 512;
  settings.height = 512;
  scene.frame(ViewName::three_quarter, 1.0);
  const Image picture = render(scene, settings);
  write_png(gallery_dir() / "arm_cutaway.png", picture);
  EXPECT_GT(spread(picture), 0.3);
}

TEST(RenderGallery, FaceOverSkull) {
  Scene scene;
  scene.add(make_icosphere(Vec3::Zero(), 80, 4), SurfaceMaterial::bone(), "skull");
  SurfaceMaterial face = SurfaceMaterial::skin();
  face.opacity = 0.45;
  scene.add(make_icosphere(Vec3(0, -5, 0), 95, 5), face, "face");
  for (int i = 0; i < 12; ++i) {
    const double a = 2 * M_PI * i / 12;
    const Vec3 dir(std::cos(a) * 0.6, -0.8, std::sin(a) * 0.6);
    LineOverlay line;
    line.from = dir.normalized() * 80;
    line.to = dir.normalized() * 96;
    scene.lines.push_back(line);
    PointOverlay point;
    point.position = line.from;
    point.label = i == 0 ? "zy" : "";
    scene.points.push_back(point);
  }
  RenderSettings settings;
  settings.width = 512;
  settings.height = 512;
  scene.frame(ViewName::front, 1.0);
  const Image picture = render(scene, settings);
  write_png(gallery_dir() / "face_over_skull.png", picture);
  EXPECT_GT(spread(picture), 0.3);
}

TEST(RenderGallery, MoistureFieldWithLegend) {
  TriMesh arm = limb(260, 45, 5);
  std::vector<double> moisture(arm.vertex_count());
  for (std::size_t i = 0; i < arm.vertex_count(); ++i) moisture[i] = 0.2 + 0.5 * (arm.positions[i][2] + 130) / 260;
  arm.vertex_fields.scalars["moisture"] = moisture;
  Scene scene;
  scene.add(arm, SurfaceMaterial::field("moisture", 0.2, 0.7, ColormapName::viridis), "arm");
  RenderSettings settings;
  settings.width = 420;
  settings.height = 512;
  scene.frame(ViewName::front, 420.0 / 512.0);
  ColourBar bar;
  bar.min = 0.2;
  bar.max = 0.7;
  bar.title = "moisture";
  bar.unit = "kg/kg";
  bar.ticks = 6;
  const Image picture = with_colour_bar(render(scene, settings), bar);
  write_png(gallery_dir() / "moisture_legend.png", picture);
  EXPECT_GT(spread(picture), 0.3);
}

TEST(RenderGallery, TimelineSheetAndTurntable) {
  std::vector<SheetCell> cells;
  RenderSettings settings;
  settings.width = 200;
  settings.height = 240;
  Camera camera;  // one camera for every state, framed on the first, so changes in size show
  for (int day = 0; day < 4; ++day) {
    const double shrink = 1.0 - 0.08 * day;
    Scene scene;
    SurfaceMaterial skin = SurfaceMaterial::skin(Vec3f(0.62f - 0.1f * day, 0.42f - 0.07f * day, 0.33f - 0.05f * day));
    scene.add(limb(260, 45 * shrink, 4), skin, "arm");
    scene.add(limb(240, 14, 3), SurfaceMaterial::bone(), "bone");
    if (day == 0) scene.frame(ViewName::left, 200.0 / 240.0);
    if (day == 0) camera = scene.camera;
    scene.camera = camera;
    cells.push_back({render(scene, settings), "day " + std::to_string(day * 10)});
  }
  const Image sheet = make_sheet(cells, 4, "Desiccation of a forearm (phantom)");
  write_png(gallery_dir() / "timeline_sheet.png", sheet);
  Scene scene;
  scene.add(make_box_mesh(Vec3(-40, -30, -20), Vec3(40, 30, 20), 2), SurfaceMaterial::clay(), "box");
  scene.add(make_icosphere(Vec3(0, 0, 45), 25, 3), SurfaceMaterial::skin(), "ball");
  const std::vector<Image> frames = render_turntable(scene, settings, 6, 15.0);
  std::vector<SheetCell> turn;
  for (std::size_t i = 0; i < frames.size(); ++i) turn.push_back({frames[i], std::to_string(i * 60) + "°"});
  write_png(gallery_dir() / "turntable_sheet.png", make_sheet(turn, 3, "Turntable"));
  EXPECT_EQ(frames.size(), 6u);
  const Image quick = render_mesh(limb(200, 40, 4), settings, "three_quarter");
  write_png(gallery_dir() / "quick_look.png", quick);
}

TEST(RenderGallery, HeadLikeSkinWithSkullCutAway) {
  TriMesh skin = make_icosphere(Vec3::Zero(), 90.0, 5);
  for (Vec3& p : skin.positions) {
    const Vec3 n = p.normalized();
    p *= 1.0 + 0.04 * std::sin(7 * n[0]) * std::sin(5 * n[1]) * std::cos(6 * n[2]) + 0.2 * n[2] * n[2];
  }
  compute_normals(skin);
  Scene scene;
  scene.add(make_icosphere(Vec3::Zero(), 70.0, 4), SurfaceMaterial::bone(), "skull");
  scene.add(std::make_shared<const TriMesh>(std::move(skin)), SurfaceMaterial::skin(), "skin");
  scene.cutaway = CutPlane{Vec3(0, 0, 0), Vec3(1, 0, 0)};
  RenderSettings settings;
  settings.width = 600;
  settings.height = 600;
  settings.samples_per_pixel = 16;
  scene.frame(ViewName::three_quarter, 1.0);
  const Image picture = render(scene, settings);
  write_png(gallery_dir() / "head_cutaway.png", picture);
  scene.cutaway.reset();
  scene.objects[1].material.opacity = 0.4;
  write_png(gallery_dir() / "head_transparent.png", render(scene, settings));
  EXPECT_GT(spread(picture), 0.3);
}
