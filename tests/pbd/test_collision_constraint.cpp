#include "pbd/collision_constraint.hpp"

#include <gtest/gtest.h>

using namespace forensim;

TEST(CollisionConstraint, PushesAPenetratingParticleOutToItsHeight) {
  const Vec3 q(0, 0, 0), n(0, 0, 1);
  const Vec3 p(0.3, -0.2, -0.5);
  EXPECT_NEAR(collision_value(p, q, n, 0.0), -0.5, 1e-15);
  const PairCorrection d = project_collision(p, q, n, 1.0, 0.0, 0.0);
  EXPECT_NEAR(collision_value(p + d.dp0, q, n, 0.0), 0.0, 1e-15);
  // Only along the normal.
  EXPECT_NEAR((p + d.dp0 - Vec3(0.3, -0.2, 0.0)).norm(), 0.0, 1e-15);
  // A negative height allows a rest depth under the surface.
  EXPECT_EQ(project_collision(p, q, n, 1.0, 0.0, -0.6).dp0, Vec3::Zero());
  // Half stiffness halves the violation.
  const PairCorrection half = project_collision(p, q, n, 1.0, 0.0, 0.0, 0.5);
  EXPECT_NEAR(collision_value(p + half.dp0, q, n, 0.0), -0.25, 1e-15);
}

TEST(CollisionConstraint, LeavesParticlesAboveAndConservesMomentum) {
  const Vec3 q(1, 1, 1), n = Vec3(1, 1, 0).normalized();
  EXPECT_EQ(project_collision(q + 0.1 * n, q, n, 1.0, 0.0, 0.0).dp0, Vec3::Zero());
  const PairCorrection d = project_collision(q - 0.4 * n, q, n, 1.0, 1.0, 0.0);
  EXPECT_LT((d.dp0 + d.dp1).norm(), 1e-15);
  EXPECT_NEAR(collision_value(q - 0.4 * n + d.dp0, q + d.dp1, n, 0.0), 0.0, 1e-12);
}
