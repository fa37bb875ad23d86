#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "mesh_processing/uv_atlas.hpp"

using namespace forensim;

namespace {

/// Chart per face of a box or cube-map direction of a sphere: the dominant axis of the face normal.
std::vector<int> dominant_axis_charts(const TriMesh& mesh) {
  std::vector<int> charts;
  for (const Vec3& n : face_normals(mesh)) {
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    charts.push_back(2 * axis + (n[axis] > 0.0 ? 1 : 0));
  }
  return charts;
}

/// Open cylinder of radius r along z from 0 to h, `around` x `along` quads, outward oriented.
TriMesh make_tube(double r, double h, int around, int along) {
  TriMesh mesh;
  for (int j = 0; j <= along; ++j) {
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * std::numbers::pi * i / around;
      mesh.positions.emplace_back(r * std::cos(a), r * std::sin(a), h * j / along);
    }
  }
  for (int j = 0; j < along; ++j) {
    for (int i = 0; i < around; ++i) {
      const Index a = j * around + i, b = j * around + (i + 1) % around, c = a + around, d = b + around;
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  }
  return mesh;
}

double uv_triangle_area(const TriMesh& mesh, std::size_t t) {
  const Vec2 a = mesh.uvs[static_cast<std::size_t>(mesh.triangle_uvs[t][0])];
  const Vec2 b = mesh.uvs[static_cast<std::size_t>(mesh.triangle_uvs[t][1])];
  const Vec2 c = mesh.uvs[static_cast<std::size_t>(mesh.triangle_uvs[t][2])];
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

}  // namespace

TEST(UvAtlas, BoxFacesAreIsometricPackedAndDisjoint) {
  const TriMesh box = make_box_mesh(Vec3(0, 0, 0), Vec3(40, 20, 10), 4);
  UvAtlasOptions options;
  options.resolution = 256;
  options.gutter_texels = 3;
  const UvAtlas atlas = make_uv_atlas(box, dominant_axis_charts(box), options);
  ASSERT_EQ(atlas.charts.size(), 6u);
  EXPECT_NEAR(atlas.stats.l2_stretch, 1.0, 1e-6);
  for (const UvChartStats& c : atlas.charts) {
    EXPECT_NEAR(c.l2_stretch, 1.0, 1e-6);
    EXPECT_NEAR(c.area_distortion, 1.0, 1e-6);
    EXPECT_EQ(c.flipped_triangles, 0u);
    EXPECT_EQ(c.self_overlaps, 0u);
  }
  EXPECT_TRUE(atlas.stats.overlap_free);
  EXPECT_FALSE(uv_triangles_overlap(atlas.mesh, 2048));
  // Inside the unit square with at least the gutter left free at the border.
  EXPECT_EQ(uv_outside_unit_square(atlas.mesh, 3.0 / 256.0 - 1e-9), 0u);
  for (std::size_t t = 0; t < box.triangles.size(); ++t) EXPECT_GT(uv_triangle_area(atlas.mesh, t), 0.0);
  // Common density: every triangle's UV area times (mm per UV unit)^2 equals its surface area.
  const double s2 = atlas.stats.mm_per_uv_unit * atlas.stats.mm_per_uv_unit;
  for (std::size_t t = 0; t < box.triangles.size(); ++t) {
    const Tri& f = box.triangles[t];
    const double area =
        triangle_area(box.positions[static_cast<std::size_t>(f[0])], box.positions[static_cast<std::size_t>(f[1])],
                      box.positions[static_cast<std::size_t>(f[2])]);
    EXPECT_NEAR(uv_triangle_area(atlas.mesh, t) * s2, area, 1e-6 * area);
  }
  // Seams: the 12 box edges, 4 mesh edges each; vertices are not duplicated.
  EXPECT_EQ(atlas.stats.seam_edge_count, 12u * 4u);
  EXPECT_EQ(atlas.mesh.positions.size(), box.positions.size());
  EXPECT_GT(atlas.mesh.uvs.size(), box.positions.size());
  EXPECT_GT(atlas.stats.packing_efficiency, 0.3);
  EXPECT_LE(atlas.stats.packing_efficiency, 1.0);
}

TEST(UvAtlas, GutterSeparatesChartsByTheRequestedTexels) {
  const TriMesh box = make_box_mesh(Vec3(0, 0, 0), Vec3(10, 10, 10), 2);
  UvAtlasOptions options;
  options.resolution = 128;
  options.gutter_texels = 4;
  const UvAtlas atlas = make_uv_atlas(box, dominant_axis_charts(box), options);
  // Bounding boxes of distinct charts are at least the gutter apart on one axis.
  std::vector<Vec2> lo(6, Vec2::Constant(1e9)), hi(6, Vec2::Constant(-1e9));
  for (std::size_t t = 0; t < box.triangles.size(); ++t) {
    const auto c = static_cast<std::size_t>(atlas.triangle_chart[t]);
    for (const Index i : atlas.mesh.triangle_uvs[t]) {
      lo[c] = lo[c].cwiseMin(atlas.mesh.uvs[static_cast<std::size_t>(i)]);
      hi[c] = hi[c].cwiseMax(atlas.mesh.uvs[static_cast<std::size_t>(i)]);
    }
  }
  const double gutter = 4.0 / 128.0;
  for (std::size_t a = 0; a < 6; ++a) {
    for (std::size_t b = a + 1; b < 6; ++b) {
      const double gap_x = std::max(lo[b].x() - hi[a].x(), lo[a].x() - hi[b].x());
      const double gap_y = std::max(lo[b].y() - hi[a].y(), lo[a].y() - hi[b].y());
      EXPECT_GE(std::max(gap_x, gap_y), gutter - 1e-9) << a << " " << b;
    }
  }
}

TEST(UvAtlas, CurvedChartsFlattenWithBoundedStretch) {
  const TriMesh sphere = make_icosphere(Vec3(0, 0, 0), 30.0, 3);
  UvAtlasOptions options;
  options.resolution = 512;
  for (const UvFlattening method : {UvFlattening::lscm, UvFlattening::arap, UvFlattening::automatic}) {
    options.flattening = method;
    const UvAtlas atlas = make_uv_atlas(sphere, dominant_axis_charts(sphere), options);
    EXPECT_TRUE(atlas.stats.overlap_free);
    EXPECT_GT(atlas.stats.l2_stretch, 1.0);  // a sphere cannot be flattened isometrically
    EXPECT_LT(atlas.stats.l2_stretch, 1.15);
    for (std::size_t t = 0; t < sphere.triangles.size(); ++t) EXPECT_GT(uv_triangle_area(atlas.mesh, t), 0.0);
    EXPECT_NEAR(uv_l2_stretch(atlas.mesh), atlas.stats.l2_stretch, 1e-9);
  }
}

TEST(UvAtlas, HalfTubesAreDevelopable) {
  const TriMesh tube = make_tube(20.0, 80.0, 48, 24);
  std::vector<int> charts;
  for (std::size_t t = 0; t < tube.triangles.size(); ++t) charts.push_back((t / 2) % 48 < 24 ? 3 : 8);
  const UvAtlas atlas = make_uv_atlas(tube, charts);
  ASSERT_EQ(atlas.charts.size(), 2u);
  EXPECT_EQ(atlas.charts[0].chart, 3);
  EXPECT_EQ(atlas.charts[1].chart, 8);
  EXPECT_LT(atlas.stats.l2_stretch, 1.01);
  EXPECT_TRUE(atlas.stats.overlap_free);
}

TEST(UvAtlas, RejectsChartsThatAreNotDisks) {
  const TriMesh sphere = make_icosphere(Vec3(0, 0, 0), 10.0, 1);
  // One chart for a closed sphere: no boundary.
  try {
    make_uv_atlas(sphere, std::vector<int>(sphere.triangles.size(), 5));
    FAIL() << "closed chart accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location(), "chart 5");
  }
  // A tube as one chart is an annulus: two boundary loops.
  const TriMesh tube = make_tube(5.0, 10.0, 12, 3);
  EXPECT_THROW(make_uv_atlas(tube, std::vector<int>(tube.triangles.size(), 0)), InputError);
  // Two triangles meeting only at a vertex.
  TriMesh bowtie;
  bowtie.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0)};
  bowtie.triangles = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_THROW(make_uv_atlas(bowtie, {0, 0}), InputError);
  // Wrong sizes and ids.
  EXPECT_THROW(make_uv_atlas(sphere, {0, 1}), InputError);
  std::vector<int> negative(sphere.triangles.size(), 0);
  negative[3] = -1;
  EXPECT_THROW(make_uv_atlas(sphere, negative), InputError);
}

TEST(UvAtlas, OverlapTestFindsOverlappingAndSparesAdjacentTriangles) {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.uvs = {Vec2(0.1, 0.1), Vec2(0.9, 0.1), Vec2(0.9, 0.9), Vec2(0.1, 0.9)};
  mesh.triangle_uvs = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_FALSE(uv_triangles_overlap(mesh, 512));  // the shared diagonal is not an overlap
  mesh.uvs.push_back(Vec2(0.7, 0.3));
  mesh.triangle_uvs[1] = {0, 2, 4};  // folds onto the first triangle's half
  EXPECT_TRUE(uv_triangles_overlap(mesh, 512));
  EXPECT_GT(uv_overlap_texels(mesh, 512), 0u);
  EXPECT_EQ(uv_outside_unit_square(mesh), 0u);
  mesh.uvs[0] = Vec2(-0.1, 0.2);
  EXPECT_EQ(uv_outside_unit_square(mesh), 1u);
}

TEST(UvAtlas, ChartsAreTurnedToTheirMinimumAreaRectangle) {
  // A flat 100 x 10 mm strip turned by 30 degrees: the packed chart's UV bounding box is the strip itself.
  TriMesh strip;
  const int n = 20;
  const double c = std::cos(0.5236), s = std::sin(0.5236);
  for (int j = 0; j <= 2; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = 100.0 * i / n, y = 5.0 * j;
      strip.positions.emplace_back(c * x - s * y, s * x + c * y, 0.0);
    }
  }
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < n; ++i) {
      const Index a = j * (n + 1) + i, b = a + 1, d = a + n + 1, e = d + 1;
      strip.triangles.push_back({a, b, e});
      strip.triangles.push_back({a, e, d});
    }
  }
  const UvAtlas atlas = make_uv_atlas(strip, std::vector<int>(strip.triangles.size(), 0));
  Vec2 lo = Vec2::Constant(1e9), hi = Vec2::Constant(-1e9);
  for (const Vec2& uv : atlas.mesh.uvs) {
    lo = lo.cwiseMin(uv);
    hi = hi.cwiseMax(uv);
  }
  const Vec2 size_mm = (hi - lo) * atlas.stats.mm_per_uv_unit;
  EXPECT_NEAR(size_mm.x(), 100.0, 0.01);  // landscape
  EXPECT_NEAR(size_mm.y(), 10.0, 0.01);
}

TEST(UvAtlas, IsIndependentOfTheThreadCount) {
  const TriMesh sphere = make_icosphere(Vec3(0, 0, 0), 30.0, 2);
  set_thread_count(1);
  const UvAtlas one = make_uv_atlas(sphere, dominant_axis_charts(sphere));
  set_thread_count(0);
  const UvAtlas all = make_uv_atlas(sphere, dominant_axis_charts(sphere));
  ASSERT_EQ(one.mesh.uvs.size(), all.mesh.uvs.size());
  for (std::size_t i = 0; i < one.mesh.uvs.size(); ++i) EXPECT_EQ(one.mesh.uvs[i], all.mesh.uvs[i]);
  EXPECT_EQ(one.mesh.triangle_uvs, all.mesh.triangle_uvs);
}
