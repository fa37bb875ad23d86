#include <gtest/gtest.h>

#include "phantoms/ct_head_phantom.hpp"
#include "phantoms/sdf.hpp"

using namespace forensim;

TEST(Sdf, PrimitivesHaveExactDistancesOnAxes) {
  EXPECT_NEAR(sdf::sphere(Vec3(3, 0, 0), Vec3::Zero(), 1), 2.0, 1e-12);
  EXPECT_NEAR(sdf::capsule(Vec3(0, 2, 5), Vec3::Zero(), Vec3(0, 0, 10), 1, 1), 1.0, 1e-12);
  EXPECT_NEAR(sdf::rounded_box(Vec3(0, 0, 3), Vec3::Zero(), Vec3(1, 1, 1), 0), 2.0, 1e-12);
  EXPECT_NEAR(sdf::ellipsoid(Vec3(4, 0, 0), Vec3::Zero(), Vec3(2, 1, 1)), 2.0, 1e-9);
  EXPECT_LT(sdf::ellipsoid(Vec3::Zero(), Vec3::Zero(), Vec3(2, 1, 1)), 0);
  EXPECT_LE(sdf::smooth_union(1.0, 2.0, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(sdf::smooth_union(1.0, 5.0, 0.5), 1.0);  // far apart: plain minimum
}

TEST(CtHeadPhantom, BoneLiesInsideSkinAndValuesFollowTissue) {
  const ScalarGrid grid = make_ct_head_phantom({4.0, 0.0, 1});
  ASSERT_GT(grid.voxel_count(), 0u);
  std::size_t bone_voxels = 0, bone_outside_skin = 0;
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        const Vec3 p = grid.index_to_world(Vec3(i, j, k));
        if (ct_phantom_bone_distance(p) < -2.0) {
          ++bone_voxels;
          if (ct_phantom_skin_distance(p) > 0) ++bone_outside_skin;
          EXPECT_GT(grid.at(i, j, k), ct_phantom_bone_iso);
        } else if (ct_phantom_skin_distance(p) > 4.0) {
          EXPECT_LT(grid.at(i, j, k), ct_phantom_skin_iso);
        }
      }
    }
  }
  EXPECT_GT(bone_voxels, 500u);
  EXPECT_EQ(bone_outside_skin, 0u);
}

TEST(CtHeadPhantom, DeterministicForASeed) {
  const ScalarGrid a = make_ct_head_phantom({6.0, 20.0, 7});
  const ScalarGrid b = make_ct_head_phantom({6.0, 20.0, 7});
  const ScalarGrid c = make_ct_head_phantom({6.0, 20.0, 8});
  EXPECT_EQ(a.values, b.values);
  EXPECT_NE(a.values, c.values);
}
