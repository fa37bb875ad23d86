#include "pbd/tracking_constraint.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace forensim;

TEST(TrackingConstraint, OneSidedProjectionReducesTheValue) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 p(u(rng), u(rng), u(rng)), t(u(rng), u(rng), u(rng));
    const double radius = 0.5;
    const double before = tracking_value(p, t, radius);
    const PairCorrection d = project_tracking(p, t, 1.0, 0.0, radius, 0.4);
    const double after = tracking_value(p + d.dp0, t + d.dp1, radius);
    if (before <= 0.0) {
      // Within the radius the constraint is satisfied: nothing moves.
      EXPECT_EQ(d.dp0, Vec3::Zero());
    } else {
      EXPECT_NEAR(after, 0.6 * before, 1e-12);
      // The tracking point of the volume (w_t = 0) stays where it is.
      EXPECT_EQ(d.dp1, Vec3::Zero());
    }
  }
}

TEST(TrackingConstraint, ConservesLinearMomentumForEqualMasses) {
  const Vec3 p(1, 2, 3), t(0, 0, 0);
  const PairCorrection d = project_tracking(p, t, 1.0, 1.0, 1.0, 1.0);
  EXPECT_LT((d.dp0 + d.dp1).norm(), 1e-14);
  EXPECT_NEAR(tracking_value(p + d.dp0, t + d.dp1, 1.0), 0.0, 1e-12);
}

TEST(TrackingConstraint, PullPointsToTheTrackingPointBeyondTheRadius) {
  const Vec3 t(0, 0, 0);
  // eq. 34: -k C n beyond r_j, zero within.
  const Vec3 pull = tracking_pull(Vec3(0, 0, 3), t, 1.0, 0.5);
  EXPECT_NEAR((pull - Vec3(0, 0, -1.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(tracking_pull(Vec3(0, 0.5, 0), t, 1.0, 0.5), Vec3::Zero());
}

TEST(TrackingConstraint, BoundedProjectionIsTheSoftProjectionCappedAtTheBound) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const Vec3 a(0.1, -0.2, 0.3);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 p(u(rng), u(rng), u(rng));
    const double radius = 0.4, bound = 1.2, k = 0.3;
    const Vec3 dp = project_tracking_bounded(p, a, radius, k, bound);
    // The soft projection (project_tracking), then the hard one at the bound.
    Vec3 q = p + project_tracking(p, a, 1.0, 0.0, radius, k).dp0;
    q += project_tracking(q, a, 1.0, 0.0, bound, 1.0).dp0;
    EXPECT_LT((p + dp - q).norm(), 1e-12);
    EXPECT_LE((p + dp - a).norm(), bound + 1e-12);
    // Along the line to the anchor only.
    EXPECT_LT(dp.cross(p - a).norm(), 1e-12);
  }
  // Within the radius nothing moves; a zero stiffness leaves only the bound.
  EXPECT_EQ(project_tracking_bounded(a + Vec3(0.3, 0, 0), a, 0.4, 1.0, 1.2), Vec3::Zero());
  EXPECT_NEAR((a + Vec3(0, 2.0, 0) + project_tracking_bounded(a + Vec3(0, 2.0, 0), a, 0.4, 0.0, 1.2) - a).norm(), 1.2,
              1e-12);
}
