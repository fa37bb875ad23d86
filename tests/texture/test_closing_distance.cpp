#include <gtest/gtest.h>

#include <cmath>

#include "core/random.hpp"
#include "texture/closing_distance.hpp"
#include "texture/convex_hull.hpp"

using namespace forensim;

TEST(ClosingDistance, KnownShapes) {
  std::vector<Vec2> circle;
  const int n = 360;  // even: antipodal vertices exist
  for (int i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * i / n;
    circle.emplace_back(50 + 12.5 * std::cos(a), 40 + 12.5 * std::sin(a));
  }
  circle.emplace_back(50, 40);  // an interior point changes nothing
  EXPECT_NEAR(closing_distance_of_points(circle), 25.0, 1e-9);
  const std::vector<Vec2> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {5, 5}, {5, 0}};
  EXPECT_NEAR(closing_distance_of_points(square), 10.0 * std::sqrt(2.0), 1e-12);
  const std::vector<Vec2> rectangle{{2, 3}, {8, 3}, {8, 11}, {2, 11}};
  EXPECT_NEAR(closing_distance(convex_hull(rectangle)), 10.0, 1e-12);  // 6 x 8 -> 10
  EXPECT_EQ(closing_distance({}), 0.0);
  EXPECT_EQ(closing_distance({{3, 4}}), 0.0);
  EXPECT_DOUBLE_EQ(closing_distance({{0, 0}, {3, 4}}), 5.0);
}

TEST(ClosingDistance, HullDiameterEqualsThePointSetDiameter) {
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    RandomStream rng(seed, 0);
    std::vector<Vec2> points;
    for (int i = 0; i < 80; ++i) points.emplace_back(rng.normal(0, 3), rng.normal(0, 1));
    double brute = 0.0;
    for (const Vec2& a : points)
      for (const Vec2& b : points) brute = std::max(brute, (a - b).norm());
    ASSERT_DOUBLE_EQ(closing_distance_of_points(points), brute);
  }
}
