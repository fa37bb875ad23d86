#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "volume/scalar_grid.hpp"

using namespace forensim;

namespace {

ScalarGrid oblique_grid() {
  ScalarGrid g = ScalarGrid::filled(5, 6, 7);
  g.spacing = Vec3(0.5, 0.75, 2.0);
  g.origin = Vec3(10.0, -20.0, 5.0);
  g.direction = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) g.at(i, j, k) = static_cast<float>(2 * i - 3 * j + 5 * k + 1);
    }
  }
  return g;
}

}  // namespace

TEST(ScalarGrid, IndexWorldRoundTrip) {
  const ScalarGrid g = oblique_grid();
  const Vec3 index(1.25, 4.5, 3.75);
  EXPECT_LT((g.world_to_index(g.index_to_world(index)) - index).norm(), 1e-12);
  // One step along j moves spacing[1] mm along the second direction column.
  const Vec3 step = g.index_to_world(Vec3(0, 1, 0)) - g.index_to_world(Vec3::Zero());
  EXPECT_NEAR(step.norm(), 0.75, 1e-12);
  EXPECT_LT((step / 0.75 - g.direction.col(1)).norm(), 1e-12);
  EXPECT_LT((g.index_to_world(Vec3::Zero()) - g.origin).norm(), 1e-12);
}

TEST(ScalarGrid, TrilinearSamplingIsExactForLinearFields) {
  const ScalarGrid g = oblique_grid();
  const Vec3 index(1.25, 4.5, 3.75);
  EXPECT_NEAR(g.sample(g.index_to_world(index)), 2 * 1.25 - 3 * 4.5 + 5 * 3.75 + 1, 1e-9);
  EXPECT_EQ(g.sample(g.index_to_world(Vec3(-1, 0, 0)), -99.0), -99.0);
  EXPECT_NEAR(g.sample(g.index_to_world(Vec3(2, 3, 4))), g.at(2, 3, 4), 1e-9);
  const auto [lo, hi] = g.value_range();
  EXPECT_EQ(lo, -3 * 5 + 1);
  EXPECT_EQ(hi, 2 * 4 + 5 * 6 + 1);
}

TEST(ScalarGrid, ValidateRejectsBadGeometry) {
  ScalarGrid g = oblique_grid();
  EXPECT_NO_THROW(g.validate("grid"));
  g.spacing[1] = 0.0;
  EXPECT_THROW(g.validate("grid"), InputError);
  g = oblique_grid();
  g.spacing[2] = std::nan("");
  EXPECT_THROW(g.validate("grid"), InputError);
  g = oblique_grid();
  g.values.pop_back();
  EXPECT_THROW(g.validate("grid"), InputError);
  g = oblique_grid();
  g.direction.col(2) = g.direction.col(0);
  EXPECT_THROW(g.validate("grid"), InputError);
  EXPECT_THROW(ScalarGrid::filled(0, 1, 1), InputError);
  EXPECT_THROW(ScalarGrid::filled(1 << 20, 1 << 20, 4), InputError);
}

TEST(ScalarGrid, ResampleKeepsExtentAndLinearValues) {
  const ScalarGrid g = oblique_grid();
  const ScalarGrid half = resample_grid(g, 2.0);
  EXPECT_EQ(half.nx, 3);
  EXPECT_EQ(half.ny, 3);
  EXPECT_EQ(half.nz, 4);
  EXPECT_LT((half.spacing - 2.0 * g.spacing).norm(), 1e-12);
  for (int k = 0; k < half.nz; ++k) {
    for (int j = 0; j < half.ny; ++j) {
      for (int i = 0; i < half.nx; ++i) {
        EXPECT_NEAR(half.at(i, j, k), g.sample(half.index_to_world(Vec3(i, j, k))), 1e-4);
      }
    }
  }
  EXPECT_THROW(resample_grid(g, 0.0), InputError);
}
