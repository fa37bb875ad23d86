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
