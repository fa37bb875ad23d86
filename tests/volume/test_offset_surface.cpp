#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "volume/offset_surface.hpp"

using namespace forensim;

namespace {

const Vec3 kCentre(12.0, -30.0, 105.0);

}  // namespace

TEST(InnerOffsetSurface, OfASphereIsTheConcentricSphereTheDepthInside) {
  const TriMesh skin = make_icosphere(kCentre, 50.0, 5);
  InnerOffsetOptions options;
  options.depth_mm = 8.0;
  const TriMesh bone = inner_offset_surface(skin, options);
  const TopologyReport topology = check_topology(bone);
  EXPECT_TRUE(topology.is_closed()) << topology.summary();
  EXPECT_TRUE(topology.is_oriented()) << topology.summary();
  EXPECT_EQ(topology.component_count, 1u);
  double worst = 0.0, sum = 0.0;
  for (const Vec3& p : bone.positions) {
    const double error = (p - kCentre).norm() - 42.0;
    worst = std::max(worst, std::abs(error));
    sum += error;
  }
  // The icosphere's flat facets lie up to 0.05 mm inside the sphere; the level set's voxels are 2 mm.
  EXPECT_LT(std::abs(sum / static_cast<double>(bone.positions.size())), 0.25);
  EXPECT_LT(worst, 0.6);
  // Outward-oriented: positive enclosed volume, that of the inner sphere.
  const double expected = 4.0 / 3.0 * std::numbers::pi * 42.0 * 42.0 * 42.0;
  EXPECT_NEAR(enclosed_volume(bone), expected, 0.02 * expected);
}

TEST(InnerOffsetSurface, KeepsOnlyThePartsThickerThanTwiceTheDepth) {
  // A big and a small ball: 8 mm inside, only the big one (radius 40) has room; the small one (radius 6) has none.
  TriMesh skin = make_icosphere(kCentre, 40.0, 4);
  const TriMesh small = make_icosphere(kCentre + Vec3(100.0, 0.0, 0.0), 6.0, 3);
  const Index offset = static_cast<Index>(skin.positions.size());
  skin.positions.insert(skin.positions.end(), small.positions.begin(), small.positions.end());
  for (const Tri& t : small.triangles) skin.triangles.push_back(Tri{t[0] + offset, t[1] + offset, t[2] + offset});
  skin.normals.clear();
  InnerOffsetOptions options;
  options.keep_largest_components = 0;
  const TriMesh bone = inner_offset_surface(skin, options);
  for (const Vec3& p : bone.positions) EXPECT_NEAR((p - kCentre).norm(), 32.0, 0.6);
}

TEST(InnerOffsetSurface, RejectsOpenSkinsBadDepthsAndBodiesTooThin) {
  TriMesh open = make_icosphere(kCentre, 50.0, 3);
  open.triangles.pop_back();
  EXPECT_THROW(inner_offset_surface(open), InputError);
  const TriMesh skin = make_icosphere(kCentre, 5.0, 3);
  InnerOffsetOptions options;
  EXPECT_THROW(inner_offset_surface(skin, options), InputError);  // 8 mm inside a 5 mm ball: nothing
  options.depth_mm = -1.0;
  EXPECT_THROW(inner_offset_surface(skin, options), InputError);
  options.depth_mm = std::nan("");
  EXPECT_THROW(inner_offset_surface(skin, options), InputError);
  // A head in the wrong unit (metres read as millimetres, 1000 times too large): refused, not gigabytes.
  EXPECT_THROW(inner_offset_surface(make_icosphere(kCentre, 100000.0, 3)), InputError);
  TriMesh bad = make_icosphere(kCentre, 50.0, 3);
  bad.positions[3].x() = std::nan("");
  EXPECT_THROW(inner_offset_surface(bad), InputError);
}
