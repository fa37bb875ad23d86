// Moisture ratio at the skin vertices from the volume's nodes through the tracking faces.

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "skin/skin_moisture.hpp"

using namespace forensim;

TEST(SkinMoisture, InterpolatesAtTheTrackingPointsAndNormalises) {
  const std::vector<double> phi = {3.0, 1.5, 0.0, 3.0, 6.0};
  const std::vector<Tri> faces = {{0, 1, 2}, {2, 3, 4}, {0, 3, 4}};
  const std::vector<Vec3> weights = {{0.5, 0.5, 0.0}, {0.5, 0.25, 0.25}, {0.0, 0.0, 1.0}};
  std::vector<double> m;
  skin_moisture_ratio(faces, weights, phi, 3.0, m);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_DOUBLE_EQ(m[0], 0.75);
  EXPECT_DOUBLE_EQ(m[1], (0.5 * 0.0 + 0.25 * 3.0 + 0.25 * 6.0) / 3.0);
  EXPECT_DOUBLE_EQ(m[2], 1.0);  // above the initial moisture: clamped
  EXPECT_THROW(skin_moisture_ratio(faces, weights, phi, 0.0, m), InputError);
  EXPECT_THROW(skin_moisture_ratio({{0, 1, 9}}, {{1, 0, 0}}, phi, 3.0, m), InputError);
  EXPECT_THROW(skin_moisture_ratio(faces, {{1, 0, 0}}, phi, 3.0, m), InputError);
}
