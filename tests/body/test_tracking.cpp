#include "body/tracking.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "body_test_meshes.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_boundary.hpp"
#include "spatial/closest_point.hpp"

using namespace forensim;

namespace {

const Vec3 box_min = Vec3::Zero();
const Vec3 box_max = Vec3::Constant(10.0);

TetMesh box_volume() {
  return make_box_tet_mesh(box_min, box_max, 4, 4, 4);
}

/// Box skin offset by `offset` mm outward (negative: inward), 10 x 10 quads per side: finer than the volume.
TriMesh box_skin(double offset) {
  return make_box_mesh(box_min - Vec3::Constant(offset), box_max + Vec3::Constant(offset), 10);
}

/// True for a vertex inside a face of the box skin (not on an edge): its normal is axis-aligned.
bool face_interior(const Vec3& p, double offset) {
  int on_side = 0;
  for (int a = 0; a < 3; ++a)
    if (std::abs(p[a] - (box_min[a] - offset)) < 1e-9 || std::abs(p[a] - (box_max[a] + offset)) < 1e-9) ++on_side;
  return on_side == 1;
}

/// Checks the properties every set of connections must have: one per vertex, tracking points on the
/// boundary, and the stored distance given back by interpolating the rest nodes.
void expect_consistent(const TrackingConnections& c, const TriMesh& skin, const TetMesh& volume) {
  ASSERT_EQ(c.size(), skin.vertex_count());
  const std::vector<TetFace> faces = tet_boundary_faces(volume);
  EXPECT_NO_THROW(validate_tracking(c, skin.vertex_count(), volume.vertex_count(), faces.size(), "test"));
  const ClosestPointQuery boundary(tet_boundary_mesh(volume));
  const std::vector<Vec3> points = tracking_points(c, volume.positions);
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c.face_nodes[i], faces[c.boundary_face[i]].vertices) << "vertex " << i;
    const double d = (points[i] - skin.positions[i]).norm();
    EXPECT_NEAR(d, c.rest_distance[i], 1e-9 * std::max(1.0, c.rest_distance[i])) << "vertex " << i;
    EXPECT_LT(boundary.query(points[i])->distance, 1e-9) << "vertex " << i;
  }
}

}  // namespace

TEST(Tracking, InflatedSkinHitsTheBoxFromOutsideAtTheOffset) {
  const double offset = 0.3;
  const TetMesh volume = box_volume();
  const TriMesh skin = box_skin(offset);
  const TrackingConnections c = compute_tracking(skin, volume);
  expect_consistent(c, skin, volume);
  std::size_t interior = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c.side[i], TrackingSide::outside) << "vertex " << i;
    EXPECT_GT(c.signed_rest_distance(i), 0.0);
    if (!face_interior(skin.positions[i], offset)) continue;
    ++interior;
    EXPECT_EQ(c.method[i], TrackingMethod::ray_negative_normal) << "vertex " << i;
    EXPECT_NEAR(c.rest_distance[i], offset, 1e-12) << "vertex " << i;
  }
  EXPECT_EQ(interior, 6u * 9 * 9);
}

TEST(Tracking, DeflatedSkinLeavesTheBoxAlongThePositiveNormal) {
  const double offset = -0.3;
  const TetMesh volume = box_volume();
  const TriMesh skin = box_skin(offset);
  const TrackingConnections c = compute_tracking(skin, volume);
  expect_consistent(c, skin, volume);
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c.side[i], TrackingSide::inside) << "vertex " << i;
    EXPECT_LT(c.signed_rest_distance(i), 0.0);
    if (!face_interior(skin.positions[i], offset)) continue;
    // The -n ray crosses the whole box (9.4 mm, beyond the 5 mm reach); +n leaves it 0.3 mm away.
    EXPECT_EQ(c.method[i], TrackingMethod::ray_positive_normal) << "vertex " << i;
    EXPECT_NEAR(c.rest_distance[i], 0.3, 1e-12) << "vertex " << i;
  }
  TrackingOptions no_positive;
  no_positive.try_positive_normal = false;
  const TrackingStats s = tracking_stats(compute_tracking(skin, volume, no_positive));
  EXPECT_EQ(s.method_counts[static_cast<int>(TrackingMethod::ray_positive_normal)], 0u);
  EXPECT_EQ(s.inside_count, skin.vertex_count());
}

TEST(Tracking, FarSkinFallsBackToClosestPoints) {
  const double offset = 20.0;
  const TetMesh volume = box_volume();
  const TriMesh skin = box_skin(offset);
  TrackingOptions options;
  options.max_distance_mm = 2.0;
  options.max_distance_edge_factor = 0.0;
  const TrackingConnections c = compute_tracking(skin, volume, options);
  expect_consistent(c, skin, volume);
  const TrackingStats s = tracking_stats(c);
  EXPECT_EQ(s.method_counts[static_cast<int>(TrackingMethod::closest_point)], skin.vertex_count());
  EXPECT_EQ(s.ray_fraction(), 0.0);
  EXPECT_EQ(s.inside_count, 0u);
  EXPECT_NEAR(s.min_distance, offset, 1e-9);
  EXPECT_NEAR(s.max_distance, offset * std::sqrt(3.0), 1e-9);  // box corners
  EXPECT_GT(s.mean_distance, s.min_distance);
  EXPECT_LT(s.mean_distance, s.max_distance);
  // With the reach raised past the offset, the skin vertices facing the box are attached by rays, at the
  // offset; the rest still find the box by closest points.
  options.max_distance_mm = 25.0;
  const TrackingConnections far = compute_tracking(skin, volume, options);
  expect_consistent(far, skin, volume);
  std::size_t rays = 0;
  for (std::size_t i = 0; i < far.size(); ++i) {
    if (far.method[i] != TrackingMethod::ray_negative_normal) continue;
    ++rays;
    if (face_interior(skin.positions[i], offset)) {
      EXPECT_NEAR(far.rest_distance[i], offset, 1e-9);
    }
  }
  EXPECT_GE(rays, 6u);  // at least the vertex facing the centre of each side of the box
}

TEST(Tracking, GivenBoundaryFacesGiveTheSameConnections) {
  const TetMesh volume = box_volume();
  const TriMesh skin = box_skin(0.3);
  const TrackingConnections a = compute_tracking(skin, volume);
  const TrackingConnections b = compute_tracking(skin, volume, tet_boundary_faces(volume));
  EXPECT_EQ(a.boundary_face, b.boundary_face);
  EXPECT_EQ(a.rest_distance, b.rest_distance);
}

TEST(Tracking, PointsFollowAnAffineDeformationOfTheNodes) {
  const TetMesh volume = box_volume();
  const TriMesh skin = box_skin(0.3);
  const TrackingConnections c = compute_tracking(skin, volume);
  Mat3 a;
  a << 0.9, 0.1, -0.05, 0.02, 0.8, 0.1, -0.1, 0.05, 1.1;
  const Vec3 b(3.0, -2.0, 0.5);
  std::vector<Vec3> deformed = volume.positions;
  for (Vec3& x : deformed) x = a * x + b;
  const std::vector<Vec3> rest_points = tracking_points(c, volume.positions);
  const std::vector<Vec3> moved = tracking_points(c, deformed);
  ASSERT_EQ(moved.size(), rest_points.size());
  for (std::size_t i = 0; i < moved.size(); ++i)
    EXPECT_LT((moved[i] - (a * rest_points[i] + b)).norm(), 1e-12 * 20.0) << "vertex " << i;
}

TEST(Tracking, FinerSphereSkinIsAttachedByRays) {
  const double r = 50.0;
  const TetMesh volume = test::make_ball_tet_mesh(r, 8);
  ASSERT_GT(test::min_tet_volume(volume), 0.0);
  const TriMesh skin = make_icosphere(Vec3::Zero(), r, 4);
  ASSERT_GT(skin.triangle_count(), 4 * tet_boundary_faces(volume).size());  // much finer than the boundary
  const TrackingConnections c = compute_tracking(skin, volume);
  expect_consistent(c, skin, volume);
  const TrackingStats s = tracking_stats(c);
  EXPECT_GE(s.ray_fraction(), 0.99);
  // The boundary is inscribed in the sphere: the skin lies outside it, by at most the chord sagitta.
  EXPECT_EQ(s.inside_count, 0u);
  EXPECT_LT(s.max_distance, 0.1 * r);
}

TEST(Tracking, SameResultAtOneAndTwoThreads) {
  const TetMesh volume = test::make_ball_tet_mesh(40.0, 6);
  TriMesh skin = make_icosphere(Vec3::Zero(), 39.0, 4);
  for (std::size_t i = 0; i < skin.positions.size(); i += 3) skin.positions[i] *= 1.02;  // mixed sides
  set_thread_count(1);
  const TrackingConnections one = compute_tracking(skin, volume);
  set_thread_count(2);
  const TrackingConnections two = compute_tracking(skin, volume);
  set_thread_count(0);
  EXPECT_EQ(one.boundary_face, two.boundary_face);
  EXPECT_EQ(one.face_nodes, two.face_nodes);
  EXPECT_EQ(one.rest_distance, two.rest_distance);
  EXPECT_EQ(one.side, two.side);
  EXPECT_EQ(one.method, two.method);
  for (std::size_t i = 0; i < one.size(); ++i) EXPECT_EQ(one.weights[i], two.weights[i]) << "vertex " << i;
  const TrackingStats s = tracking_stats(one);
  EXPECT_GT(s.inside_count, 0u);
  EXPECT_LT(s.inside_count, one.size());
}

TEST(Tracking, RejectsBadInput) {
  const TriMesh skin = box_skin(0.3);
  EXPECT_THROW(compute_tracking(skin, TetMesh{}), InputError);
  TetMesh bad = box_volume();
  bad.tets[3][2] = static_cast<Index>(bad.positions.size());
  EXPECT_THROW(compute_tracking(skin, bad), InputError);
  TrackingOptions negative;
  negative.max_distance_mm = -1.0;
  EXPECT_THROW(compute_tracking(skin, box_volume(), negative), InputError);

  const TetMesh volume = box_volume();
  std::vector<TetFace> bad_faces = tet_boundary_faces(volume);
  bad_faces[4].vertices[1] = -1;
  EXPECT_THROW(compute_tracking(skin, volume, bad_faces), InputError);
  EXPECT_THROW(compute_tracking(skin, volume, std::vector<TetFace>{}), InputError);

  const TrackingConnections c = compute_tracking(skin, volume);
  const std::vector<Vec3> too_few(volume.positions.begin(), volume.positions.begin() + 3);
  EXPECT_THROW(tracking_points(c, too_few), InputError);
  const std::size_t faces = tet_boundary_faces(volume).size();
  TrackingConnections broken = c;
  broken.weights[7] = Vec3(0.5, 0.6, -0.1);
  EXPECT_THROW(validate_tracking(broken, skin.vertex_count(), volume.vertex_count(), faces, "t"), InputError);
  broken = c;
  broken.boundary_face[2] = static_cast<Index>(faces);
  EXPECT_THROW(validate_tracking(broken, skin.vertex_count(), volume.vertex_count(), faces, "t"), InputError);
  broken = c;
  broken.rest_distance.pop_back();
  EXPECT_THROW(validate_tracking(broken, skin.vertex_count(), volume.vertex_count(), faces, "t"), InputError);
}

TEST(Tracking, EmptySkinHasNoConnections) {
  const TrackingConnections c = compute_tracking(TriMesh{}, box_volume());
  EXPECT_EQ(c.size(), 0u);
  EXPECT_EQ(tracking_stats(c).count, 0u);
  EXPECT_EQ(tracking_points(c, box_volume().positions).size(), 0u);
}

TEST(Tracking, InsideVerticesKeepTheNearerLeavingHit) {
  // A 1 mm slab; two skin vertices inside it with normals up. 0.2 mm above the bottom, the -n ray leaves
  // through the bottom first; 0.9 mm above it, the +n ray leaves through the top first.
  const TetMesh volume = make_box_tet_mesh(Vec3::Zero(), Vec3(20.0, 20.0, 1.0), 4, 4, 1);
  TriMesh skin;
  skin.positions = {Vec3(10.1, 10.2, 0.2), Vec3(10.1, 10.2, 0.9)};
  skin.normals = {Vec3::UnitZ(), Vec3::UnitZ()};
  const TrackingConnections c = compute_tracking(skin, volume);
  expect_consistent(c, skin, volume);
  EXPECT_EQ(c.method[0], TrackingMethod::ray_negative_normal);
  EXPECT_EQ(c.method[1], TrackingMethod::ray_positive_normal);
  EXPECT_EQ(c.side[0], TrackingSide::inside);
  EXPECT_EQ(c.side[1], TrackingSide::inside);
  EXPECT_NEAR(c.rest_distance[0], 0.2, 1e-12);
  EXPECT_NEAR(c.rest_distance[1], 0.1, 1e-12);
  const std::vector<Vec3> points = tracking_points(c, volume.positions);
  EXPECT_NEAR(points[0].z(), 0.0, 1e-12);
  EXPECT_NEAR(points[1].z(), 1.0, 1e-12);
}
