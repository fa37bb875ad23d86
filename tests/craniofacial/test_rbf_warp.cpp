// The RBF warp of eq. 1 (Kähler et al. 2003): interpolation, affine reproduction, identity, side conditions,
// the cheap target updates and degenerate input.
#include "craniofacial/rbf_warp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"

using namespace forensim;

namespace {

constexpr double head_mm = 250.0;  // size of the landmark cloud: a head
constexpr double tolerance = 1e-9 * head_mm;

std::vector<Vec3> random_points(std::size_t n, std::uint64_t seed, double extent = head_mm) {
  RandomStream rng(seed, 0);
  std::vector<Vec3> points(n);
  for (Vec3& p : points) {
    p = Vec3(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)) * extent + Vec3(10, -20, 30);
  }
  return points;
}

std::vector<Vec3> perturbed(const std::vector<Vec3>& points, double amount_mm, std::uint64_t seed) {
  RandomStream rng(seed, 1);
  std::vector<Vec3> out = points;
  for (Vec3& p : out) p += Vec3(rng.normal(), rng.normal(), rng.normal()) * amount_mm;
  return out;
}

double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

}  // namespace

TEST(RbfWarp, InterpolatesEveryLandmarkPair) {
  for (const std::size_t n : {4u, 12u, 40u, 150u}) {
    const auto sources = random_points(n, 10 + n);
    const auto targets = perturbed(sources, 12.0, 20 + n);
    const RbfWarp warp(sources, targets);
    EXPECT_LT(warp.max_landmark_residual(), tolerance) << n << " landmarks";
    EXPECT_LT(max_distance(warp.evaluate_batch(sources), targets), tolerance);
  }
}

TEST(RbfWarp, SatisfiesTheSideConditions) {
  const auto sources = random_points(30, 3);
  const RbfWarp warp(sources, perturbed(sources, 10.0, 4));
  const Eigen::MatrixX3d c = warp.radial_weights();
  Vec3 sum = Vec3::Zero();
  Mat3 moment = Mat3::Zero();
  for (std::size_t i = 0; i < sources.size(); ++i) {
    sum += c.row(static_cast<Eigen::Index>(i)).transpose();
    moment += c.row(static_cast<Eigen::Index>(i)).transpose() * sources[i].transpose();
  }
  EXPECT_LT(sum.norm(), 1e-10);
  EXPECT_LT(moment.norm(), 1e-10 * head_mm);
}

TEST(RbfWarp, ReproducesAnyAffineMapExactly) {
  RandomStream rng(7, 0);
  for (int trial = 0; trial < 5; ++trial) {
    Mat3 a;
    for (int i = 0; i < 9; ++i) a(i / 3, i % 3) = rng.uniform(-1.5, 1.5);
    a += Mat3::Identity();
    const Vec3 t(rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50));
    const auto sources = random_points(25, 100 + static_cast<std::uint64_t>(trial));
    std::vector<Vec3> targets;
    for (const Vec3& p : sources) targets.push_back(a * p + t);
    const RbfWarp warp(sources, targets);
    const auto probes = random_points(500, 200 + static_cast<std::uint64_t>(trial), 2.0 * head_mm);
    const auto warped = warp.evaluate_batch(probes);
    const double scale = std::max(1.0, a.norm());
    for (std::size_t i = 0; i < probes.size(); ++i) {
      ASSERT_LT((warped[i] - (a * probes[i] + t)).norm(), scale * tolerance) << "probe " << i;
    }
    EXPECT_LT((warp.linear_part() - a).norm(), 1e-10 * scale);
    EXPECT_LT((warp.translation() - t).norm(), scale * tolerance);
    EXPECT_LT(warp.radial_weights().norm(), 1e-10 * scale);
  }
}

TEST(RbfWarp, OfASetOntoItselfIsTheIdentity) {
  const auto sources = random_points(40, 5);
  const RbfWarp warp(sources, sources);
  const auto probes = random_points(1000, 6, 1.5 * head_mm);
  EXPECT_LT(max_distance(warp.evaluate_batch(probes), probes), tolerance);
}

TEST(RbfWarp, IsSmoothBetweenLandmarks) {
  // phi(r) = r in 3D is the biharmonic spline: displacements between landmarks stay within the range of the
  // landmark displacements for a single moved landmark (no overshoot beyond a modest factor).
  const auto sources = random_points(30, 8);
  auto targets = sources;
  targets[0] += Vec3(0, 0, 10);
  const RbfWarp warp(sources, targets);
  for (const Vec3& p : random_points(2000, 9)) {
    ASSERT_LT((warp(p) - p).norm(), 20.0);
  }
}

TEST(RbfWarp, SetTargetsAndSetTargetMatchAFreshWarp) {
  const auto sources = random_points(35, 11);
  RbfWarp warp(sources, perturbed(sources, 5.0, 12));
  const auto new_targets = perturbed(sources, 8.0, 13);
  warp.set_targets(new_targets);
  const RbfWarp fresh(sources, new_targets);
  const auto probes = random_points(300, 14);
  EXPECT_LT(max_distance(warp.evaluate_batch(probes), fresh.evaluate_batch(probes)), tolerance);

  auto moved = new_targets;
  moved[7] += Vec3(3.0, -4.0, 12.0);
  warp.set_target(7, moved[7]);
  const RbfWarp fresh_moved(sources, moved);
  EXPECT_LT(max_distance(warp.evaluate_batch(probes), fresh_moved.evaluate_batch(probes)), tolerance);
  EXPECT_LT(warp.max_landmark_residual(), tolerance);
}

TEST(RbfPointWarp, MatchesTheWarpAndMovesOneTargetCheaply) {
  const auto sources = random_points(45, 21);
  auto targets = perturbed(sources, 6.0, 22);
  const RbfWarp warp(sources, targets);
  const auto points = random_points(3000, 23);
  const RbfPointWarp cached(warp, points);
  auto warped = cached.warp(targets);
  EXPECT_LT(max_distance(warped, warp.evaluate_batch(points)), tolerance);

  const Vec3 delta(-7.0, 2.5, 9.0);
  cached.move_target(12, delta, warped);
  targets[12] += delta;
  EXPECT_LT(max_distance(warped, RbfWarp(sources, targets).evaluate_batch(points)), tolerance);
  // Cardinal functions are 1 at their own landmark and 0 at the others; they sum to 1 everywhere.
  const RbfPointWarp at_landmarks(warp, sources);
  for (std::size_t i = 0; i < sources.size(); ++i) {
    for (std::size_t j = 0; j < sources.size(); ++j) {
      ASSERT_NEAR(at_landmarks.cardinal_values()(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)),
                  i == j ? 1.0 : 0.0, 1e-9);
    }
  }
  for (Eigen::Index v = 0; v < cached.cardinal_values().rows(); v += 97) {
    EXPECT_NEAR(cached.cardinal_values().row(v).sum(), 1.0, 1e-9);
  }
}

TEST(RbfWarp, SameResultAtAnyThreadCount) {
  const auto sources = random_points(60, 31);
  const auto targets = perturbed(sources, 9.0, 32);
  const auto points = random_points(20000, 33);
  set_thread_count(1);
  const auto one = RbfWarp(sources, targets).evaluate_batch(points);
  const auto one_cached = RbfPointWarp(RbfWarp(sources, targets), points).warp(targets);
  set_thread_count(0);
  const auto all = RbfWarp(sources, targets).evaluate_batch(points);
  const auto all_cached = RbfPointWarp(RbfWarp(sources, targets), points).warp(targets);
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(one[i], all[i]);
    ASSERT_EQ(one_cached[i], all_cached[i]);
  }
}

TEST(RbfWarp, RejectsDegenerateInput) {
  const auto good = random_points(10, 41);
  // Fewer than 4.
  EXPECT_THROW(
      RbfWarp(std::vector<Vec3>(good.begin(), good.begin() + 3), std::vector<Vec3>(good.begin(), good.begin() + 3)),
      InputError);
  // Coincident sources.
  auto coincident = good;
  coincident[6] = coincident[2];
  try {
    RbfWarp(coincident, good);
    FAIL() << "coincident sources accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("2 and 6"), std::string::npos) << e.what();
  }
  // All in one plane, and on one line.
  std::vector<Vec3> plane, line;
  for (int i = 0; i < 12; ++i) {
    plane.emplace_back(i * 7.0, (i * i) % 5 * 11.0, 0.0);
    line.emplace_back(i * 3.0, i * 2.0, -i * 1.0);
  }
  EXPECT_THROW(RbfWarp(plane, plane), InputError);
  EXPECT_THROW(RbfWarp(line, line), InputError);
  // Non-finite values.
  auto nan_source = good;
  nan_source[4].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(RbfWarp(nan_source, good), InputError);
  auto inf_target = good;
  inf_target[1].z() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(RbfWarp(good, inf_target), InputError);
  // Sizes that differ.
  EXPECT_THROW(RbfWarp(good, std::vector<Vec3>(good.begin(), good.end() - 1)), InputError);
  RbfWarp warp(good, good);
  EXPECT_THROW(warp.set_target(0, Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0)), InputError);
  EXPECT_THROW(warp.set_target(99, Vec3::Zero()), InputError);
  EXPECT_THROW(RbfPointWarp(warp, nan_source), InputError);
}
