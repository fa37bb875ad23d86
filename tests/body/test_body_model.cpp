#include "body/body_model.hpp"

#include <gtest/gtest.h>

#include "body_test_meshes.hpp"
#include "core/error.hpp"
#include "phantoms/arm_phantom.hpp"
#include "phantoms/phantom_surface.hpp"
#include "spatial/closest_point.hpp"

using namespace forensim;
using test::box_model;

TEST(BodyModel, AssemblesBoundaryTrackingAndParts) {
  const BodyModel m = box_model();
  EXPECT_NO_THROW(m.validate("box body"));
  EXPECT_EQ(m.boundary_faces.size(), 6u * 9 * 2);
  EXPECT_EQ(m.tracking.size(), m.skin.vertex_count());
  ASSERT_EQ(m.skin_vertex_parts.size(), m.skin.vertex_count());
  ASSERT_EQ(m.tet_parts.size(), m.volume.tet_count());
  for (std::size_t i = 0; i < m.skin.vertex_count(); ++i)
    EXPECT_EQ(m.skin_vertex_parts[i], m.skin.positions[i].x() < 5.0 ? 0 : 1);
  std::size_t left = 0;
  for (int p : m.tet_parts) left += p == 0;
  EXPECT_GT(left, 0u);
  EXPECT_LT(left, m.tet_parts.size());
  EXPECT_EQ(m.volume.label(0), tissue_bone);  // labels travel with the volume
}

TEST(BodyModel, ValidateFindsInconsistencies) {
  const BodyModel good = box_model();
  BodyModel m = good;
  m.tracking.face_nodes[5][0] = m.tracking.face_nodes[5][1];
  EXPECT_THROW(m.validate("box body"), InputError);
  m = good;
  m.boundary_faces.pop_back();
  EXPECT_THROW(m.validate("box body"), InputError);
  m = good;
  m.skin_vertex_parts[3] = 2;
  EXPECT_THROW(m.validate("box body"), InputError);
  m = good;
  m.tet_parts.pop_back();
  EXPECT_THROW(m.validate("box body"), InputError);
  m = good;
  m.tracking.side.pop_back();  // one skin vertex without a side
  EXPECT_THROW(m.validate("box body"), InputError);
  try {
    m.validate("box body");
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "box body");
    EXPECT_EQ(e.location(), "tracking side");
  }
}

TEST(BodyModel, RejectsPartIndicesWithoutNames) {
  TetMesh volume = make_box_tet_mesh(Vec3::Zero(), Vec3::Constant(10.0), 2, 2, 2);
  TriMesh skin = make_box_mesh(Vec3::Zero(), Vec3::Constant(10.0), 2);
  EXPECT_THROW(make_body_model(volume, skin, {"only"}, [](const Vec3&) { return 1; }), InputError);
  const BodyModel no_parts = make_body_model(volume, skin);
  EXPECT_TRUE(no_parts.skin_vertex_parts.empty());
  EXPECT_NO_THROW(no_parts.validate("no parts"));
}

// The arm phantom's skin (2 mm iso-surface) over a coarse stand-in volume: the 5 mm grid cubes whose centre
// lies inside the skin. Its staircase boundary lies within a cube diagonal of the skin, so every skin vertex
// must be tied to a point within two cube sizes.
TEST(BodyModel, ArmPhantomSkinIsTiedToACoarseVolume) {
  const ArmPhantom arm;
  const double cube = 5.0;
  TetMesh volume = test::make_inside_cube_volume(arm, cube);
  TriMesh skin = phantom_surface(arm, PhantomSurface::skin, 2.0);
  ASSERT_GT(volume.tet_count(), 0u);
  ASSERT_GT(skin.vertex_count(), 1000u);
  const BodyModel m = make_body_model(std::move(volume), std::move(skin), arm.part_names(),
                                      [&](const Vec3& p) { return arm.part_at(p); });
  EXPECT_NO_THROW(m.validate("arm body"));
  const TrackingStats s = tracking_stats(m.tracking);
  EXPECT_EQ(s.count, m.skin.vertex_count());
  EXPECT_LE(s.max_distance, 2.0 * cube);
  EXPECT_GT(s.ray_fraction(), 0.5);
  const std::vector<Vec3> points = tracking_points(m.tracking, m.volume.positions);
  for (std::size_t i = 0; i < points.size(); ++i)
    ASSERT_LE((points[i] - m.skin.positions[i]).norm(), 2.0 * cube) << "skin vertex " << i;
  std::vector<bool> seen(arm.part_names().size(), false);
  for (int p : m.skin_vertex_parts) seen[p] = true;
  EXPECT_GE(std::count(seen.begin(), seen.end(), true), 2);
}
