#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/iso_surface.hpp"
#include "volume/nrrd_reader.hpp"
#include "volume/taubin_smooth.hpp"

using namespace forensim;

namespace {

// Signed "inside-ness" of a sphere sampled on a grid: r - |p - c| (positive inside), grid spacing `h` mm.
ScalarGrid sphere_field(int n, double h, const Vec3& center, double radius, const Mat3& direction = Mat3::Identity()) {
  ScalarGrid g = ScalarGrid::filled(n, n, n);
  g.spacing = Vec3::Constant(h);
  g.direction = direction;
  g.origin = Vec3(-5.0, 3.0, 10.0);
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        g.at(i, j, k) = static_cast<float>(radius - (g.index_to_world(Vec3(i, j, k)) - center).norm());
      }
    }
  }
  return g;
}

void expect_closed_oriented(const TriMesh& mesh) {
  const TopologyReport r = check_topology(mesh);
  EXPECT_TRUE(r.is_closed()) << r.summary();
  EXPECT_TRUE(r.is_manifold()) << r.summary();
  EXPECT_TRUE(r.is_oriented()) << r.summary();
  EXPECT_EQ(r.isolated_vertex_count, 0u);
  EXPECT_GT(enclosed_volume(mesh), 0.0) << "triangles face inwards";
}

}  // namespace

TEST(IsoSurface, SphereIsClosedOrientedAndAccurate) {
  const double h = 0.5, r = 6.0;
  const ScalarGrid g = sphere_field(40, h, Vec3(5.0, 13.0, 20.0), r);
  const TriMesh mesh = extract_iso_surface(g, 0.0);
  expect_closed_oriented(mesh);
  EXPECT_EQ(check_topology(mesh).component_count, 1u);
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(enclosed_volume(mesh), exact, 0.015 * exact);
  for (const Vec3& p : mesh.positions) EXPECT_NEAR((p - Vec3(5.0, 13.0, 20.0)).norm(), r, 0.5 * h);
}

TEST(IsoSurface, ReflectedAxesKeepOutwardOrientation) {
  Mat3 d = Mat3::Identity();
  d(0, 0) = -1.0;  // a left-handed index-to-world map
  const double h = 0.5, r = 5.0;
  const Vec3 center = Vec3(-5.0, 3.0, 10.0) + Vec3(-10.0, 10.0, 10.0);
  const ScalarGrid g = sphere_field(40, h, center, r, d);
  const TriMesh mesh = extract_iso_surface(g, 0.0);
  expect_closed_oriented(mesh);
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(enclosed_volume(mesh), exact, 0.02 * exact);
}

TEST(IsoSurface, ObjectTouchingTheBorderIsClosed) {
  // A sphere cut by the volume's faces: the grid is all inside near one corner.
  const ScalarGrid g = sphere_field(20, 1.0, Vec3(-5.0, 3.0, 10.0), 12.0);
  const TriMesh mesh = extract_iso_surface(g, 0.0);
  expect_closed_oriented(mesh);
  const BoundingBox box = bounding_box(mesh.positions);
  // The padding closes the cut within one voxel beyond the border samples.
  EXPECT_LE(box.min.x(), -5.0);
  EXPECT_GE(box.min.x(), -6.0);
  // Everything fully inside: a closed box around the whole lattice.
  ScalarGrid full = ScalarGrid::filled(4, 5, 6, 1.0f);
  const TriMesh cube = extract_iso_surface(full, 0.5);
  expect_closed_oriented(cube);
}

TEST(IsoSurface, NothingAboveIsoGivesEmptyMesh) {
  const ScalarGrid g = ScalarGrid::filled(5, 5, 5, 0.0f);
  EXPECT_TRUE(extract_iso_surface(g, 1.0).positions.empty());
}

TEST(IsoSurface, KeepLargestComponentAndResample) {
  ScalarGrid g = ScalarGrid::filled(40, 20, 20, 0.0f);
  for (int k = 0; k < 20; ++k) {
    for (int j = 0; j < 20; ++j) {
      for (int i = 0; i < 40; ++i) {
        const double big = 7.0 - (Vec3(i, j, k) - Vec3(10, 10, 10)).norm();
        const double small = 3.0 - (Vec3(i, j, k) - Vec3(30, 10, 10)).norm();
        g.at(i, j, k) = static_cast<float>(std::max(big, small));
      }
    }
  }
  EXPECT_EQ(check_topology(extract_iso_surface(g, 0.0)).component_count, 2u);
  IsoSurfaceOptions options;
  options.keep_largest_components = 1;
  const TriMesh one = extract_iso_surface(g, 0.0, options);
  EXPECT_EQ(check_topology(one).component_count, 1u);
  EXPECT_NEAR(bounding_box(one.positions).center().x(), 10.0, 0.5);
  options.resample_factor = 2.0;
  const TriMesh coarse = extract_iso_surface(g, 0.0, options);
  expect_closed_oriented(coarse);
  EXPECT_LT(coarse.triangle_count(), one.triangle_count() / 2);
  const double exact = 4.0 / 3.0 * std::numbers::pi * 343.0;
  EXPECT_NEAR(enclosed_volume(coarse), exact, 0.1 * exact);  // radius 3.5 coarse voxels
}

TEST(TaubinSmooth, SmoothsNoiseWithoutShrinking) {
  const ScalarGrid g = sphere_field(40, 0.5, Vec3(5.0, 13.0, 20.0), 6.0);
  TriMesh mesh = extract_iso_surface(g, 0.0);
  const double before = enclosed_volume(mesh);
  const auto radial_spread = [](const TriMesh& m) {
    double sum = 0.0, sum2 = 0.0;
    for (const Vec3& p : m.positions) {
      const double d = (p - Vec3(5.0, 13.0, 20.0)).norm();
      sum += d;
      sum2 += d * d;
    }
    const double n = double(m.positions.size());
    return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
  };
  const double spread_before = radial_spread(mesh);
  taubin_smooth(mesh, 10);
  expect_closed_oriented(mesh);
  EXPECT_LT(radial_spread(mesh), spread_before);
  EXPECT_NEAR(enclosed_volume(mesh), before, 0.01 * before);  // plain Laplacian would lose several percent
}

// The VTK headsq CT (64 x 64 x 93, 3.2 x 3.2 x 1.5 mm; neck to just above the orbits) at the iso-values of VTK's
// Medical examples. Bounds come from the data (SOURCE.md and per-slice extents): the skin is widest at the ears
// (about 186 mm, 58 voxels), about 176-185 mm front to back and cut at the volume's top and bottom (140 mm); the skull
// is about 145 mm wide at the top slice.
TEST(IsoSurface, HeadCtSkinAndBoneAreClosedAndHeadSized) {
  FORENSIM_REQUIRE_DATA(path, "ct-head-headsq/quarter.nhdr");
  const ScalarGrid ct = read_nrrd(path);
  struct Case {
    double iso;
    Vec3 min_size, max_size;
    double min_ml, max_ml;
  };
  const Case cases[] = {{500.0, Vec3(150, 160, 125), Vec3(210, 205, 145), 1500.0, 3500.0},
                        {1150.0, Vec3(120, 140, 125), Vec3(170, 190, 145), 300.0, 1000.0}};
  for (const Case& c : cases) {
    const TriMesh mesh = extract_iso_surface(ct, c.iso);
    const TopologyReport r = check_topology(mesh);
    const Vec3 size = bounding_box(mesh.positions).size();
    const double ml = enclosed_volume(mesh) / 1000.0;
    std::printf("iso %.0f: %zu triangles, bbox %.1f x %.1f x %.1f mm, %.0f ml, %s\n", c.iso, mesh.triangle_count(),
                size.x(), size.y(), size.z(), ml, r.summary().c_str());
    EXPECT_TRUE(r.is_closed()) << r.summary();
    EXPECT_TRUE(r.is_manifold()) << r.summary();
    EXPECT_TRUE(r.is_oriented()) << r.summary();
    EXPECT_EQ(r.degenerate_triangle_count, 0u);
    EXPECT_TRUE((size.array() >= c.min_size.array()).all() && (size.array() <= c.max_size.array()).all())
        << size.transpose();
    EXPECT_GT(ml, c.min_ml);
    EXPECT_LT(ml, c.max_ml);
    EXPECT_GT(mesh.triangle_count(), 20000u);
    EXPECT_LT(mesh.triangle_count(), 200000u);
  }
}

TEST(IsoSurface, NonFiniteSamplesGiveFiniteClosedSurface) {
  ScalarGrid g = sphere_field(20, 1.0, Vec3(4.5, 12.5, 19.5), 5.0);
  g.at(10, 10, 10) = std::numeric_limits<float>::infinity();  // inside
  g.at(1, 1, 1) = -std::numeric_limits<float>::infinity();    // outside
  g.at(2, 2, 2) = std::numeric_limits<float>::quiet_NaN();    // missing: outside
  const TriMesh mesh = extract_iso_surface(g, 0.0);
  expect_closed_oriented(mesh);
  for (const Vec3& p : mesh.positions) ASSERT_TRUE(p.allFinite());
  EXPECT_THROW(extract_iso_surface(g, std::nan("")), InputError);
}
