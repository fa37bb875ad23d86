#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/random.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "spatial/closest_point.hpp"

using namespace forensim;

namespace {

struct Brute {
  double distance = std::numeric_limits<double>::infinity();
  Vec3 point = Vec3::Zero();
};

Brute brute_force(const TriMesh& mesh, const Vec3& p) {
  Brute best;
  for (const Tri& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Vec3& b = mesh.positions[t[1]];
    const Vec3& c = mesh.positions[t[2]];
    const Vec3 bary = closest_point_on_triangle(p, a, b, c);
    const Vec3 q = bary[0] * a + bary[1] * b + bary[2] * c;
    const double d = (q - p).norm();
    if (d < best.distance) {
      best.distance = d;
      best.point = q;
    }
  }
  return best;
}

void expect_equal_to_brute_force(const TriMesh& mesh, int count, std::uint64_t seed) {
  const ClosestPointQuery query(mesh);
  RandomStream rng(seed, 0);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const double spread = (i % 4 == 0) ? 20.0 : 2.5;  // some far away
    points.emplace_back(rng.uniform(-spread, spread), rng.uniform(-spread, spread), rng.uniform(-spread, spread));
  }
  const auto batch = query.query_batch(points);
  for (int i = 0; i < count; ++i) {
    const Brute ref = brute_force(mesh, points[i]);
    const auto got = query.query(points[i]);
    ASSERT_TRUE(got);
    EXPECT_NEAR(got->distance, ref.distance, 1e-12 * (1.0 + ref.distance)) << "point " << i;
    EXPECT_LT((got->point - ref.point).norm(), 1e-6) << "point " << i;
    const Tri& t = mesh.triangles[got->triangle];
    const Vec3 from_bary = got->barycentric[0] * mesh.positions[t[0]] + got->barycentric[1] * mesh.positions[t[1]] +
                           got->barycentric[2] * mesh.positions[t[2]];
    EXPECT_LT((from_bary - got->point).norm(), 1e-12);
    EXPECT_NEAR(got->barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(got->barycentric.minCoeff(), 0.0);
    ASSERT_TRUE(batch[i]);
    EXPECT_EQ(batch[i]->triangle, got->triangle);
    EXPECT_EQ(batch[i]->distance, got->distance);
    // A bound just above or below the true distance keeps or drops the answer.
    EXPECT_TRUE(query.query(points[i], ref.distance * (1 + 1e-9) + 1e-12));
    if (ref.distance > 1e-6) {
      EXPECT_FALSE(query.query(points[i], ref.distance * (1 - 1e-6)));
    }
  }
}

}  // namespace

TEST(ClosestPointOnTriangle, VoronoiRegions) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_TRUE(closest_point_on_triangle(Vec3(0.5, 0.5, 3), a, b, c).isApprox(Vec3(0.5, 0.25, 0.25)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(-1, -1, 1), a, b, c).isApprox(Vec3(1, 0, 0)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(5, -1, 0), a, b, c).isApprox(Vec3(0, 1, 0)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(1, -3, 0), a, b, c).isApprox(Vec3(0.5, 0.5, 0)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(2, 2, -1), a, b, c).isApprox(Vec3(0, 0.5, 0.5)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(-4, 1, 0), a, b, c).isApprox(Vec3(0.5, 0, 0.5)));
  // Collinear (degenerate) triangle: closest point of the segment.
  const Vec3 bary = closest_point_on_triangle(Vec3(1, 1, 0), a, b, Vec3(1, 0, 0));
  const Vec3 q = bary[0] * a + bary[1] * b + bary[2] * Vec3(1, 0, 0);
  EXPECT_NEAR((q - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
}

TEST(ClosestPointQuery, EqualsBruteForceOnIcosphere) {
  expect_equal_to_brute_force(make_icosphere(Vec3(0.2, 0.1, -0.3), 1.3, 3), 1200, 31);
}

TEST(ClosestPointQuery, EqualsBruteForceOnBox) {
  expect_equal_to_brute_force(make_box_mesh(Vec3(-1, -0.5, -1.5), Vec3(1.5, 1, 0.5), 4), 2000, 32);
}

TEST(ClosestPointQuery, EqualsBruteForceOnSphereWithHole) {
  TriMesh sphere = make_icosphere(Vec3::Zero(), 1.4, 3);
  std::vector<bool> keep(sphere.triangle_count(), true);
  for (int f = 0; f < 40; ++f) keep[f] = false;
  expect_equal_to_brute_force(extract_triangles(sphere, keep), 1200, 33);
}

TEST(ClosestPointQuery, FarFromOrigin) {
  const Vec3 centre(2.0e5, 1.0e5, -3.0e5);
  const TriMesh sphere = make_icosphere(centre, 10.0, 3);
  const ClosestPointQuery query(sphere);
  RandomStream rng(34, 0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 p = centre + Vec3(rng.uniform(-15, 15), rng.uniform(-15, 15), rng.uniform(-15, 15));
    const auto got = query.query(p);
    ASSERT_TRUE(got);
    EXPECT_NEAR(got->distance, brute_force(sphere, p).distance, 1e-9);
  }
}

TEST(ClosestPointQuery, EmptyMeshAndBadInput) {
  EXPECT_FALSE(ClosestPointQuery(TriMesh{}).query(Vec3::Zero()));
  const ClosestPointQuery query(make_icosphere(Vec3::Zero(), 1.0, 1));
  EXPECT_THROW((void)query.query(Vec3(0, std::numeric_limits<double>::infinity(), 0)), InputError);
  EXPECT_THROW((void)query.query(Vec3::Zero(), -1.0), InputError);
  EXPECT_FALSE(query.query(Vec3(10, 0, 0), 5.0));
}

TEST(ClosestPointQuery, FreeFunctionMatchesQuery) {
  const TriMesh mesh = make_icosphere(Vec3::Zero(), 1.0, 2);
  const ClosestPointQuery query(mesh);
  RandomStream rng(35, 0);
  for (int i = 0; i < 300; ++i) {
    const Vec3 p(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    const auto a = query.query(p, 0.5);
    const auto b = closest_point(mesh, p, 0.5);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_EQ(a->distance, b->distance);
      EXPECT_EQ(a->triangle, b->triangle);  // both break ties towards the lower index
    }
  }
}

TEST(ClosestPointQuery, BoundedBatchEqualsUnbounded) {
  // Bounds from a point on the mesh (as the previous closest point of a point that moved), loose bounds, wrong
  // (too small) bounds and no bound: every answer equals the unbounded one bit for bit.
  const TriMesh mesh = make_box_mesh(Vec3(-1, -0.5, -1.5), Vec3(1.5, 1, 0.5), 4);
  const ClosestPointQuery query(mesh);
  RandomStream rng(36, 0);
  std::vector<Vec3> points;
  std::vector<double> bounds;
  for (int i = 0; i < 800; ++i) {
    const double spread = (i % 4 == 0) ? 20.0 : 2.5;
    const Vec3 p(rng.uniform(-spread, spread), rng.uniform(-spread, spread), rng.uniform(-spread, spread));
    points.push_back(p);
    const Vec3& on_mesh = mesh.positions[static_cast<std::size_t>(i) % mesh.positions.size()];
    const double d = brute_force(mesh, p).distance;
    switch (i % 4) {
      case 0:
        bounds.push_back((p - on_mesh).norm());
        break;
      case 1:
        bounds.push_back(3.0 * d + 1.0);
        break;
      case 2:
        bounds.push_back(0.5 * d);  // wrong: searched again without a bound
        break;
      default:
        bounds.push_back(std::numeric_limits<double>::infinity());
    }
  }
  const auto plain = query.query_batch(points);
  const auto bounded = query.query_batch_bounded(points, bounds);
  ASSERT_EQ(bounded.size(), plain.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_TRUE(bounded[i]) << "point " << i;
    EXPECT_EQ(bounded[i]->triangle, plain[i]->triangle) << "point " << i;
    EXPECT_EQ(bounded[i]->distance, plain[i]->distance) << "point " << i;
    EXPECT_EQ(bounded[i]->point, plain[i]->point) << "point " << i;
  }
  EXPECT_THROW((void)query.query_batch_bounded(points, std::vector<double>(3, 1.0)), InputError);
  bounds[5] = -1.0;
  EXPECT_THROW((void)query.query_batch_bounded(points, bounds), InputError);
}
