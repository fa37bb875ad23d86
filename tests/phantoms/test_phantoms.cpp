#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "phantoms/arm_phantom.hpp"
#include "phantoms/phantom.hpp"
#include "phantoms/sdf.hpp"

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

// The head's bone distance skips its teeth and its cervical spine (plain minima) where their boxes lie farther
// than the distance so far: it must still be at most every one of those shapes' distances (a wrong skip leaves
// a larger value where a tooth or a vertebra is the nearest bone). Points fill boxes around both groups.
TEST(HeadPhantom, BoneDistanceIsAtMostEveryToothAndVertebra) {
  const auto phantom = make_phantom("head");
  std::vector<std::pair<Vec3, Vec3>> boxes = {{Vec3(-40, -95, -62), Vec3(40, -40, -24)},
                                              {Vec3(-25, 0, -150), Vec3(25, 70, -15)}};
  std::size_t checked = 0, on_group = 0;
  for (const auto& [lo, hi] : boxes) {
    for (double x = lo.x(); x <= hi.x(); x += 1.7) {
      for (double y = lo.y(); y <= hi.y(); y += 1.3) {
        for (double z = lo.z(); z <= hi.z(); z += 1.1) {
          const Vec3 p(x, y, z);
          const Vec3 q(std::abs(x), y, z);
          double group = std::numeric_limits<double>::infinity();
          for (int row = 0; row < 2; ++row) {
            for (int t = 0; t < 8; ++t) {
              const double angle = (t + 0.5) / 8.0 * 1.35;
              const Vec3 c(std::sin(angle) * 24.0, -78.0 + (1.0 - std::cos(angle)) * 34.0, row == 0 ? -39.0 : -47.0);
              group = std::min(group, sdf::rounded_box(q, c, Vec3(3.2, 3.0, 4.2), 1.5));
            }
          }
          for (int v = 0; v < 7; ++v) {
            const double vz = -34.0 - v * 16.0;
            group = std::min(group, sdf::rounded_box(p, Vec3(0, 24 + v * 0.8, vz), Vec3(9, 8, 6.2), 3.0));
            group = std::min(group, sdf::capsule(p, Vec3(0, 30 + v * 0.8, vz), Vec3(0, 44 + v, vz - 3), 3.5, 3.0));
          }
          const double d = phantom->bone_distance(p);
          // 1e-9 mm: the tooth centres' trigonometry may round differently here than in the phantom.
          ASSERT_LE(d, group + 1e-9) << "at " << p.transpose();
          on_group += std::abs(d - group) <= 1e-9 ? 1 : 0;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(on_group, checked / 20) << "the groups are the nearest bone at many of the points";
}
