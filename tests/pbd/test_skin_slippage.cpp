#include "pbd/skin_slippage.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

using namespace forensim;

TEST(SkinSlippage, StiffnessFollowsEquation35) {
  SlippageLaw law;
  law.initial_stiffness = 0.8;
  law.decrease_below = 0.4;
  law.zero_below = 0.1;
  // Fresh skin keeps k_t.
  EXPECT_DOUBLE_EQ(tracking_stiffness(1.0, law), 0.8);
  EXPECT_DOUBLE_EQ(tracking_stiffness(0.4, law), 0.8);
  // Between the thresholds: m k_t / tau_d, falling with the moisture.
  EXPECT_DOUBLE_EQ(tracking_stiffness(0.3, law), 0.3 * 0.8 / 0.4);
  EXPECT_LT(tracking_stiffness(0.2, law), tracking_stiffness(0.3, law));
  EXPECT_DOUBLE_EQ(tracking_stiffness(0.1, law), 0.1 * 0.8 / 0.4);
  // Below the lower threshold the skin is detached.
  EXPECT_EQ(tracking_stiffness(0.099, law), 0.0);
  EXPECT_EQ(tracking_stiffness(0.0, law), 0.0);
}

TEST(SkinSlippage, RadiusOpensFromZeroForWetSkinToRmaxForDrySkin) {
  SlippageLaw law;
  law.initial_stiffness = 0.8;
  law.decrease_below = 0.4;
  law.zero_below = 0.1;
  const double r_max = 2.5;
  // Wet skin is tracked: radius 0 however stiff the tracking is.
  EXPECT_EQ(slip_radius_mm(1.0, law, r_max), 0.0);
  EXPECT_EQ(slip_radius_mm(0.4, law, r_max), 0.0);
  // Dry skin (below tau_n) slides within r_max.
  EXPECT_EQ(slip_radius_mm(0.099, law, r_max), r_max);
  EXPECT_EQ(slip_radius_mm(0.0, law, r_max), r_max);
  // Between the thresholds eq. 33 with the stiffness of eq. 35: r_j = (1 - k_j / k_t) r_max.
  for (double m : {0.1, 0.2, 0.35})
    EXPECT_NEAR(slip_radius_mm(m, law, r_max), (1.0 - tracking_stiffness(m, law) / law.initial_stiffness) * r_max,
                1e-12)
        << m;
  // Monotone: the drier the skin, the larger the radius and the weaker the pull; always within [0, r_max].
  double last_radius = -1.0, last_stiffness = 2.0;
  for (int k = 100; k >= 0; --k) {
    const double m = 0.01 * k;
    const double r = slip_radius_mm(m, law, r_max), stiffness = tracking_stiffness(m, law);
    EXPECT_GE(r, last_radius) << m;
    EXPECT_LE(stiffness, last_stiffness) << m;
    EXPECT_GE(r, 0.0);
    EXPECT_LE(r, r_max);
    last_radius = r;
    last_stiffness = stiffness;
  }
  // The slip fraction does not depend on k_t (so also a tracking stiffness of 0 opens the radius with drying).
  SlippageLaw loose = law;
  loose.initial_stiffness = 0.0;
  EXPECT_EQ(slip_fraction(0.2, loose), slip_fraction(0.2, law));
  EXPECT_EQ(slip_fraction(0.5, loose), 0.0);
}

TEST(SkinSlippage, RejectsBadThresholds) {
  SlippageLaw law;
  law.zero_below = 0.5;
  law.decrease_below = 0.3;
  EXPECT_THROW(law.validate("law"), InputError);
  law = SlippageLaw{};
  law.initial_stiffness = 1.5;
  EXPECT_THROW(law.validate("law"), InputError);
  EXPECT_NO_THROW(SlippageLaw{}.validate("law"));
}
