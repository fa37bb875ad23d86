#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/random.hpp"
#include "texture/convex_hull.hpp"

using namespace forensim;

namespace {

// True when every point lies inside or on the convex polygon (clockwise, y-up).
bool contains_all(const std::vector<Vec2>& hull, const std::vector<Vec2>& points) {
  for (const Vec2& p : points)
    for (std::size_t i = 0; i < hull.size(); ++i)
      if (turn_determinant(hull[i], hull[(i + 1) % hull.size()], p) > 1e-9) return false;
  return true;
}

}  // namespace

TEST(ConvexHull, SquareWithInteriorCollinearAndDuplicatePoints) {
  const std::vector<Vec2> points{{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}, {1, 0}, {0, 1}, {2, 2}, {0, 0}, {1, 2}};
  const std::vector<Vec2> hull = convex_hull(points);
  const std::vector<Vec2> expected{{0, 0}, {0, 2}, {2, 2}, {2, 0}};  // clockwise (y-up) from the smallest point
  EXPECT_EQ(hull, expected);
  EXPECT_DOUBLE_EQ(polygon_signed_area(hull), -4.0);
  EXPECT_EQ(convex_hull_monotone_chain(points), expected);
}

TEST(ConvexHull, DegenerateInputs) {
  EXPECT_TRUE(convex_hull({}).empty());
  EXPECT_EQ(convex_hull({{1, 1}}).size(), 1u);
  EXPECT_EQ(convex_hull({{1, 1}, {1, 1}, {1, 1}}).size(), 1u);
  const std::vector<Vec2> line = convex_hull({{3, 3}, {0, 0}, {1, 1}, {2, 2}, {1, 1}});
  const std::vector<Vec2> expected{{0, 0}, {3, 3}};
  EXPECT_EQ(line, expected);
  EXPECT_EQ(convex_hull_monotone_chain({{3, 3}, {0, 0}, {1, 1}, {2, 2}}), expected);
  const std::vector<Vec2> vertical = convex_hull({{1, 5}, {1, 2}, {1, 3}});
  EXPECT_EQ(vertical, (std::vector<Vec2>{{1, 2}, {1, 5}}));
  EXPECT_THROW(convex_hull({{0, 0}, {std::nan(""), 1}}), InputError);
}

TEST(ConvexHull, Algorithm41AgreesWithMonotoneChainOnRandomSets) {
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    RandomStream rng(seed, 0);
    const int n = static_cast<int>(rng.uniform_int(0, 60));
    std::vector<Vec2> points;
    // Small integer grids force collinear triples, equal x and duplicates.
    const int grid = static_cast<int>(rng.uniform_int(1, 8));
    for (int i = 0; i < n; ++i) {
      if (seed % 3 == 0)
        points.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1));
      else
        points.emplace_back(static_cast<double>(rng.uniform_int(0, grid)),
                            static_cast<double>(rng.uniform_int(0, grid)));
    }
    const std::vector<Vec2> a = convex_hull(points), b = convex_hull_monotone_chain(points);
    ASSERT_EQ(a, b) << "seed " << seed;
    ASSERT_TRUE(contains_all(a, points)) << "seed " << seed;
    if (a.size() >= 3) {
      ASSERT_LT(polygon_signed_area(a), 0.0);     // clockwise
      for (std::size_t i = 0; i < a.size(); ++i)  // strictly convex: no collinear vertices kept
        ASSERT_LT(turn_determinant(a[i], a[(i + 1) % a.size()], a[(i + 2) % a.size()]), 0.0);
    }
  }
}
