#include <gtest/gtest.h>

#include "core/error.hpp"
#include "phantoms/arm_phantom.hpp"
#include "phantoms/phantom.hpp"

using namespace forensim;

namespace {
// Samples the phantom's box on a lattice and returns the smallest skin depth over bone (mm): the minimum
// of -skin_distance over points inside bone. Also counts points inside bone and inside skin.
struct DepthStats {
  double min_depth_over_bone = 1e9;
  std::size_t bone_points = 0, skin_points = 0;
};
DepthStats sample(const Phantom& phantom, double step) {
  DepthStats s;
  const BoundingBox box = phantom.bounds();
  for (double z = box.min.z(); z <= box.max.z(); z += step) {
    for (double y = box.min.y(); y <= box.max.y(); y += step) {
      for (double x = box.min.x(); x <= box.max.x(); x += step) {
        const Vec3 p(x, y, z);
        const double skin = phantom.skin_distance(p);
        if (skin < 0) ++s.skin_points;
        if (phantom.bone_distance(p) < 0) {
          ++s.bone_points;
          s.min_depth_over_bone = std::min(s.min_depth_over_bone, -skin);
        }
      }
    }
  }
  return s;
}
}  // namespace

class PhantomTest : public ::testing::TestWithParam<std::string> {};

TEST_P(PhantomTest, BoneLiesUnderAtLeastTwoMillimetresOfTissue) {
  const auto phantom = make_phantom(GetParam());
  const DepthStats s = sample(*phantom, 3.0);
  EXPECT_GT(s.bone_points, 200u);
  EXPECT_GT(s.skin_points, 10 * s.bone_points / 4);
  EXPECT_GE(s.min_depth_over_bone, 2.0);  // on a 3 mm lattice
}

TEST_P(PhantomTest, SkinStaysInsideBoundsAndPartsAreNamed) {
  const auto phantom = make_phantom(GetParam());
  const BoundingBox box = phantom->bounds();
  // The box faces are outside (or on) the skin.
  for (double u = 0; u <= 1.0; u += 0.05) {
    for (double v = 0; v <= 1.0; v += 0.05) {
      const Vec3 a = box.min + Vec3(u, v, 0).cwiseProduct(box.size());
      const Vec3 b = box.min + Vec3(0, u, v).cwiseProduct(box.size());
      const Vec3 c = box.min + Vec3(u, 0, v).cwiseProduct(box.size());
      EXPECT_GE(phantom->skin_distance(a), -1e-9);
      EXPECT_GE(phantom->skin_distance(b), -1e-9);
      EXPECT_GE(phantom->skin_distance(c), -1e-9);
    }
  }
  std::vector<int> seen(phantom->part_names().size(), 0);
  for (double z = box.min.z(); z <= box.max.z(); z += 4) {
    for (double y = box.min.y(); y <= box.max.y(); y += 4) {
      for (double x = box.min.x(); x <= box.max.x(); x += 4) {
        if (phantom->skin_distance(Vec3(x, y, z)) >= 0) continue;
        const int part = phantom->part_at(Vec3(x, y, z));
        ASSERT_GE(part, 0);
        ASSERT_LT(part, static_cast<int>(seen.size()));
        ++seen[static_cast<std::size_t>(part)];
      }
    }
  }
  for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_GT(seen[k], 0) << phantom->part_names()[k];
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, PhantomTest, ::testing::Values("arm", "head"));

TEST(ArmPhantom, FingersAreThinAndTheForearmThick) {
  const ArmPhantom arm;
  for (const auto& digit : arm.digits()) {
    // Depth at the middle of the proximal segment: the finger's inscribed radius.
    const Vec3 mid = 0.5 * (digit.joints[0] + digit.joints[1]);
    EXPECT_LT(-arm.skin_distance(mid), 13.0) << digit.name;
    EXPECT_GT(-arm.skin_distance(mid), 6.0) << digit.name;
  }
  EXPECT_GT(-arm.skin_distance(Vec3(100, 0, 0)), 22.0);
}

TEST(Phantom, UnknownNameListsTheKnownOnes) {
  try {
    (void)make_phantom("leg");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("arm, head"), std::string::npos) << e.what();
  }
}
