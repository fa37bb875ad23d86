#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/job.hpp"
#include "wound/uv_cylinder.hpp"
#include "wound/wound_job.hpp"
#include "wound_fixture.hpp"

using namespace forensim;

namespace {
// Largest jump of a distance image between the texels on the two sides of the cylinder's UV seam (first and
// last covered columns of each row), over rows where the wound or its glow reaches the seam.
double seam_jump(const WoundCanvas& c, const Image& d, int last_column) {
  double worst = 0.0;
  const int left = 0 - c.region.x0;
  const int right = last_column - c.region.x0;
  if (left < 0 || right >= c.width()) return -1.0;
  for (int y = 0; y < c.height(); ++y) {
    const float a = d.at(left, y), b = d.at(right, y);
    if (!std::isfinite(a) && !std::isfinite(b)) continue;
    if (!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, static_cast<double>(std::abs(a - b)));
  }
  return worst;
}
}  // namespace

TEST(WoundCanvas, SurfaceDistancesAreContinuousAcrossTheUvSeam) {
  const int size = 128;
  const auto c = test::fixture_canvas(size, DistanceMode::surface);
  // The cylinder's UVs span u in [0, 2 pi r / s] = [0, 1] here (circumference 62.8 mm > length 60 mm).
  ASSERT_EQ(c->region.x0, 0);
  ASSERT_EQ(c->region.x1, size);
  const double texel_mm = 1.0 / c->texels_per_mm;
  // Texels on either side of the seam are one texel apart on the surface.
  EXPECT_LT(seam_jump(*c, c->outside_mm, size - 1), 1.5 * texel_mm);
  EXPECT_LT(seam_jump(*c, c->inside_mm, size - 1), 1.5 * texel_mm);
  // The shape agrees across the seam too.
  int inside_left = 0, inside_right = 0;
  for (int y = 0; y < c->height(); ++y) {
    inside_left += c->shape.at(0, y) >= 0.5f;
    inside_right += c->shape.at(size - 1, y) >= 0.5f;
  }
  EXPECT_GT(inside_left, 0);
  EXPECT_NEAR(inside_left, inside_right, 2);
  // The thesis's way in UV space: the same stroke is cut at the seam (the distances jump).
  const auto uv = test::fixture_canvas(size, DistanceMode::uv);
  EXPECT_GT(seam_jump(*uv, uv->outside_mm, size - 1), 5.0 * texel_mm);
}

TEST(WoundCanvas, DistancesAreZeroOnTheRightSideAndDensityFromUvs) {
  const auto c = test::fixture_canvas(128);
  // 128 texels over s = 2 pi 10 mm.
  EXPECT_NEAR(c->texels_per_mm, 128.0 / (2.0 * M_PI * 10.0), 0.02);
  for (int y = 0; y < c->height(); ++y)
    for (int x = 0; x < c->width(); ++x) {
      if (c->shape.at(x, y) >= 0.5f) {
        ASSERT_EQ(c->outside_mm.at(x, y), 0.0f);
        ASSERT_LE(c->inside_mm.at(x, y), 3.0f + 1.0f / c->texels_per_mm);  // within the brush radius
      } else {
        ASSERT_EQ(c->inside_mm.at(x, y), 0.0f);
        ASSERT_GT(c->outside_mm.at(x, y), 0.0f);
      }
    }
  // Closing distance: the wound's diameter, between the two strokes' far ends (> 20 mm apart here).
  EXPECT_GT(c->closing_distance_mm, 20.0);
  EXPECT_LT(c->closing_distance_mm, 40.0);
  const auto hull = test::fixture_canvas(128, DistanceMode::uv, ShapeMode::convex_hull);
  EXPECT_GT(hull->wound_texels, 0u);
}

TEST(WoundCanvas, RejectsStrokesOffTheMeshAndMeshesWithoutUvs) {
  const TriMesh mesh = test::fixture_mesh();
  const UvRaster raster = rasterize_uv(mesh, 32, 32);
  Image upper, lower;
  default_skin_maps(32, 32, 1, upper, lower);
  WoundStroke off;
  off.points = {Vec3(100, 0, 30)};
  EXPECT_THROW(make_wound_canvas(mesh, raster, {off}, upper, lower, {}), InputError);
  EXPECT_THROW(make_wound_canvas(mesh, raster, {}, upper, lower, {}), InputError);
  TriMesh no_uv = mesh;
  no_uv.triangle_uvs.clear();
  EXPECT_THROW(mesh_texels_per_mm(no_uv, 32, 32), InputError);
}

TEST(WoundJob, ReadsStrokesAndRejectsUnknownKeys) {
  const TriMesh mesh = test::fixture_mesh();
  auto doc = JobDocument::parse(R"({"type": "abrasion", "distance": "uv",
      "strokes": [{"uv": [[0.5, 0.5], [0.6, 0.5]], "radius_mm": 2}],
      "keys": [{"phase": "vasoconstriction", "time": "0s"}, {"phase": "scab", "time": "5d"},
               {"phase": "scab", "time": "9d"}]})",
                                "test job");
  const WoundJob job = read_wound_job(doc.root(), mesh);
  doc.check_all_used();
  ASSERT_EQ(job.strokes.size(), 1u);
  EXPECT_EQ(job.canvas.distance, DistanceMode::uv);
  ASSERT_EQ(job.timeline.size(), 3u);
  EXPECT_EQ(job.timeline[1].key, job.timeline[2].key);  // a hold pair shares its key position
  EXPECT_DOUBLE_EQ(job.timeline[1].time_s, 5 * 86400.0);
  EXPECT_NEAR(job.strokes[0].points[0].z(), 0.5 * 2.0 * M_PI * 10.0, 1e-6);

  auto typo = JobDocument::parse(R"({"strokes": [{"uv": [[0.5, 0.5]], "radius": 2}]})", "typo job");
  read_wound_job(typo.root(), mesh);
  EXPECT_THROW(typo.check_all_used(), JobError);
  auto off = JobDocument::parse(R"({"strokes": [{"uv": [[0.5, 1.5]]}]})", "off job");
  EXPECT_THROW(read_wound_job(off.root(), mesh), JobError);
  auto bad_time = JobDocument::parse(
      R"({"strokes": [{"uv": [[0.5, 0.5]]}], "keys": [{"phase": "scab", "time": "3 days"}]})", "time job");
  EXPECT_THROW(read_wound_job(bad_time.root(), mesh), JobError);
}
