#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/error.hpp"
#include "core/random.hpp"
#include "spatial/nearest_point.hpp"

using namespace forensim;

namespace {

std::vector<Vec3> random_cloud(std::size_t n, std::uint64_t seed) {
  RandomStream rng(seed, 0);
  std::vector<Vec3> points(n);
  for (Vec3& p : points) p = Vec3(rng.uniform(-50, 50), rng.uniform(-30, 30), rng.uniform(0, 80));
  return points;
}

}  // namespace

TEST(NearestPointIndex, FindsTheBruteForceNearestPointInAClusteredCloud) {
  std::vector<Vec3> points = random_cloud(3000, 7);
  // A dense cluster and duplicated points, where a tree's pruning is most tested.
  RandomStream rng(8, 0);
  for (int i = 0; i < 500; ++i) points.emplace_back(rng.normal(10, 0.05), rng.normal(0, 0.05), rng.normal(40, 0.05));
  points.push_back(points[12]);
  const NearestPointIndex index(points);
  ASSERT_EQ(index.size(), points.size());
  const std::vector<Vec3> queries = random_cloud(2000, 9);
  const std::vector<NearestPoint> batch = index.nearest_batch(queries);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const NearestPoint brute = nearest_point_brute_force(points, queries[i]);
    EXPECT_NEAR(batch[i].distance, brute.distance, 1e-12) << i;
    EXPECT_NEAR((points[batch[i].index] - queries[i]).norm(), batch[i].distance, 1e-12) << i;
    const NearestPoint single = index.nearest(queries[i]);
    EXPECT_EQ(single.index, batch[i].index) << i;
  }
  // A query far outside the cloud, and one on a point.
  const Vec3 far(1e4, -2e4, 3e4);
  EXPECT_NEAR(index.nearest(far).distance, nearest_point_brute_force(points, far).distance, 1e-9);
  EXPECT_EQ(index.nearest(points[100]).distance, 0.0);
}

TEST(NearestPointIndex, RejectsNonFinitePointsAndQueriesAndAnEmptyCloud) {
  std::vector<Vec3> points = random_cloud(10, 1);
  points[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(NearestPointIndex bad(points), InputError);
  const NearestPointIndex empty(std::vector<Vec3>{});
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_THROW(empty.nearest(Vec3::Zero()), InputError);
  EXPECT_TRUE(empty.nearest_batch({}).empty());
  const NearestPointIndex index(random_cloud(10, 2));
  EXPECT_THROW(index.nearest(Vec3(0, std::numeric_limits<double>::infinity(), 0)), InputError);
}
