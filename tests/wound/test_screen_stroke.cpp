// Strokes drawn on the screen (chapter 4.2.1, eqs. 4.1 to 4.3): the barycentric coordinates from areas
// equal the exact ray/triangle ones, recorded points lie under their pixels and carry the UV of their
// surface point, rays off the mesh are skipped, and a screen stroke in a job paints the same wound as its
// recorded surface points.
#include <gtest/gtest.h>

#include <random>

#include "core/error.hpp"
#include "core/job.hpp"
#include "spatial/ray_caster.hpp"
#include "wound/screen_stroke.hpp"
#include "wound/wound_job.hpp"
#include "wound_fixture.hpp"

namespace forensim {
namespace {

TEST(ScreenStroke, BarycentricFromAreasEqualsTheExactIntersection) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coord(-20.0, 20.0), unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a(coord(rng), coord(rng), coord(rng)), b(coord(rng), coord(rng), coord(rng)),
        c(coord(rng), coord(rng), coord(rng));
    double r = unit(rng), t = unit(rng);
    if (r + t > 1.0) r = 1.0 - r, t = 1.0 - t;
    const Vec3 p = (1.0 - r - t) * a + r * b + t * c;
    const Vec3 normal = (b - a).cross(c - a).normalized();
    double hit_t = 0.0;
    Vec3 exact;
    ASSERT_TRUE(ray_triangle_intersect(p + 50.0 * normal, -normal, a, b, c, 0.0, 1e9, hit_t, exact));
    const Vec3 w = barycentric_from_areas(a, b, c, p);
    EXPECT_NEAR((w - exact).cwiseAbs().maxCoeff(), 0.0, 1e-9) << "trial " << trial;
    EXPECT_NEAR((barycentric_blend(w, a, b, c) - p).norm(), 0.0, 1e-9);  // eq. 4.1 gives P back
  }
  EXPECT_EQ(barycentric_from_areas(Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Ones()), Vec3(1, 0, 0));
}

TEST(ScreenStroke, RecordedPointsLieUnderTheirPixelsWithTheirUvs) {
  const TriMesh mesh = test::fixture_mesh();
  StrokeScreen screen;
  screen.width = screen.height = 200;
  screen.camera = Camera::look_at(Vec3(150, 0, 30), Vec3(0, 0, 30), Vec3::UnitZ(), 30.0);
  // A stroke across the cylinder's front, and one pixel in the corner, off the mesh.
  const std::vector<Vec2> pixels = {{80, 90}, {100, 100}, {120, 110}, {1, 1}};
  const RecordedStroke rec = record_screen_stroke(mesh, screen, pixels, 2.0);
  ASSERT_EQ(rec.points.size(), 3u);
  EXPECT_EQ(rec.missed, 1u);
  EXPECT_EQ(rec.stroke.points.size(), 3u);
  EXPECT_DOUBLE_EQ(rec.stroke.radius_mm, 2.0);
  for (const RecordedPoint& p : rec.points) {
    Vec2 pixel;
    double depth = 0.0;
    ASSERT_TRUE(screen.camera.project(p.position, screen.width, screen.height, &pixel, &depth));
    EXPECT_NEAR((pixel - pixels[p.screen_index]).norm(), 0.0, 1e-6);
    EXPECT_NEAR(Vec2(p.position.x(), p.position.y()).norm(), 10.0, 0.2);  // on the cylinder's facets
    EXPECT_GT(p.position.x(), 0.0);                                       // the visible (near) side
    const auto back = surface_point_at_uv(mesh, p.uv);                    // eq. 4.3 inverts to the point
    ASSERT_TRUE(back.has_value());
    EXPECT_NEAR((*back - p.position).norm(), 0.0, 1e-6);
  }
  EXPECT_THROW(record_screen_stroke(mesh, screen, {{1, 1}, {199, 1}}, 2.0), InputError);
  EXPECT_THROW(record_screen_stroke(mesh, screen, {{NAN, 1}}, 2.0), InputError);
  EXPECT_THROW(record_screen_stroke(mesh, screen, {{100, 100}}, 0.0), InputError);
  TriMesh no_uvs = mesh;
  no_uvs.uvs.clear();
  no_uvs.triangle_uvs.clear();
  EXPECT_THROW(record_screen_stroke(no_uvs, screen, {{100, 100}}, 2.0), InputError);
}

TEST(ScreenStroke, JobScreenStrokePaintsTheSameWoundAsItsSurfacePoints) {
  const TriMesh mesh = test::fixture_mesh();
  const std::string camera = R"("camera": {"eye": [150, 0, 30], "target": [0, 0, 30], "up": [0, 0, 1],
                                  "width": 200, "height": 200})";
  JobDocument screen_doc = JobDocument::parse(
      R"({"strokes": [{"screen": [[80, 90], [100, 100], [120, 110], [1, 1]], "radius_mm": 2, )" + camera + "}]}",
      "screen job");
  const WoundJob from_screen = read_wound_job(screen_doc.root(), mesh);
  screen_doc.check_all_used();
  ASSERT_EQ(from_screen.strokes.size(), 1u);
  ASSERT_EQ(from_screen.strokes[0].points.size(), 3u);
  nlohmann::json points = nlohmann::json::array();
  for (const Vec3& p : from_screen.strokes[0].points) points.push_back({p.x(), p.y(), p.z()});
  JobDocument point_doc =
      JobDocument::parse(nlohmann::json{{"strokes", {{{"points", points}, {"radius_mm", 2}}}}}.dump(), "point job");
  const WoundJob from_points = read_wound_job(point_doc.root(), mesh);
  const UvRaster raster = rasterize_uv(mesh, 96, 96);
  Image upper, lower;
  default_skin_maps(96, 96, 3, upper, lower);
  const WoundCanvas a = make_wound_canvas(mesh, raster, from_screen.strokes, upper, lower, from_screen.canvas);
  const WoundCanvas b = make_wound_canvas(mesh, raster, from_points.strokes, upper, lower, from_points.canvas);
  EXPECT_GT(a.wound_texels, 0u);
  EXPECT_EQ(a.wound_texels, b.wound_texels);
  EXPECT_EQ(a.region.x0, b.region.x0);
  EXPECT_EQ(a.shape.data(), b.shape.data());

  // A named view framed on the mesh also records (the cylinder seen from its front, -Y).
  JobDocument view_doc =
      JobDocument::parse(R"({"strokes": [{"screen": [[512, 512]], "camera": {"view": "front"}}]})", "view job");
  const WoundJob from_view = read_wound_job(view_doc.root(), mesh);
  view_doc.check_all_used();
  ASSERT_EQ(from_view.strokes[0].points.size(), 1u);
  EXPECT_LT(from_view.strokes[0].points[0].y(), 0.0);

  // Bad screen strokes name their key.
  for (
      const std::string bad :
      {R"({"strokes": [{"screen": [[1, 1]], "camera": {"eye": [150, 0, 30], "target": [0, 0, 30], "up": [0, 0, 1], "width": 200, "height": 200}}]})",
       R"({"strokes": [{"screen": [[1]], "camera": {"view": "front"}}]})",
       R"({"strokes": [{"screen": [[1, 2]], "camera": {"view": "sideways"}}]})",
       R"({"strokes": [{"screen": [[1, 2]], "uv": [[0.5, 0.5]]}]})",
       R"({"strokes": [{"screen": [[1, 2]], "camera": {"eye": [0, 0, 0], "target": [0, 0, 0], "up": [0, 0, 1]}}]})"}) {
    JobDocument doc = JobDocument::parse(bad, "bad job");
    try {
      read_wound_job(doc.root(), mesh);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const JobError& e) {
      EXPECT_NE(std::string(e.what()).find("strokes"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace forensim
