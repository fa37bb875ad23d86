#include "craniofacial/face_expression.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <map>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/skin_spring_kernels.hpp"
#include "template_head_fixture.hpp"

namespace forensim {
namespace {

const FaceExpressions& expressions() {
  static const FaceExpressions e = [] {
    const TemplateHead& head = test::coarse_template_head();
    return FaceExpressions(head.skin, head.skull, shape_muscles(head.muscles, head.skin));
  }();
  return e;
}

Vec3 skin_landmark(const std::string& name) {
  for (const TemplateSkinLandmark& l : test::coarse_template_head().skin_landmarks) {
    if (l.name == name) return l.position;
  }
  ADD_FAILURE() << "no skin landmark " << name;
  return Vec3::Zero();
}

/// Presets solved once per test program.
const FaceExpression& cached_preset(const std::string& name) {
  static std::map<std::string, FaceExpression> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, expressions().preset(name)).first;
  return it->second;
}

std::vector<Vec3> track(const FaceExpression& e, const std::vector<Vec3>& points) {
  return track_skin_points(test::coarse_template_head().skin, e.skin_positions, points);
}

TEST(SkinSpringKernels, SpringGradientAndHessianMatchFiniteDifferences) {
  const Vec3 a(0.3, -0.2, 1.1), b(-0.5, 0.4, 0.2);
  const double rest = 0.8, k = 2.5, h = 1e-6;
  const SpringTerm t = spring_term(a, b, rest, k, false, false);
  Vec6 x;
  x << a, b;
  for (int i = 0; i < 6; ++i) {
    Vec6 xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    const SpringTerm tp = spring_term(xp.head<3>(), xp.tail<3>(), rest, k, false, false);
    const SpringTerm tm = spring_term(xm.head<3>(), xm.tail<3>(), rest, k, false, false);
    EXPECT_NEAR((tp.energy - tm.energy) / (2 * h), t.gradient(i), 1e-6);
    for (int j = 0; j < 6; ++j) EXPECT_NEAR((tp.gradient(j) - tm.gradient(j)) / (2 * h), t.hessian(j, i), 1e-5);
  }
  // Compressed: the projected Hessian is positive semi-definite, a tension-only spring is slack.
  const SpringTerm c = spring_term(a, b, 3.0, k, false, true);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat6>(c.hessian).eigenvalues().minCoeff(), -1e-12);
  const SpringTerm slack = spring_term(a, b, 3.0, k, true, true);
  EXPECT_EQ(slack.energy, 0.0);
  EXPECT_EQ(slack.gradient.norm(), 0.0);
}

TEST(MuscleContraction, EnergyGradientMatchesFiniteDifferences) {
  const MuscleContractionSolver& solver = expressions().solver();
  const SkinMuscleModel& m = solver.model();
  std::vector<double> act(m.muscle_names.size(), 0.0);
  for (std::size_t k = 0; k < act.size(); ++k) act[k] = 0.1 + 0.8 * static_cast<double>(k % 5) / 4.0;
  std::vector<Vec3> x = m.node_rest_positions;
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] += 0.3 * Vec3(std::sin(1.3 * i), std::cos(0.7 * i), std::sin(2.1 * i));
  std::vector<double> g;
  solver.energy(x, act, &g);
  const double h = 1e-6;
  // Nodes: a skin vertex, a free fibre sample (the last one) and its skin attachment corner.
  const std::size_t nodes[] = {0, x.size() - 1, static_cast<std::size_t>(m.attachment_triangle.back()[0])};
  for (std::size_t n : nodes) {
    for (int r = 0; r < 3; ++r) {
      std::vector<Vec3> xp = x, xm = x;
      xp[n](r) += h;
      xm[n](r) -= h;
      const double fd = (solver.energy(xp, act) - solver.energy(xm, act)) / (2 * h);
      EXPECT_NEAR(fd, g[3 * n + static_cast<std::size_t>(r)], 1e-5 * std::max(1.0, std::abs(fd))) << n << " " << r;
    }
  }
}

TEST(FaceExpression, NeutralLeavesSkinExactlyInPlace) {
  const FaceExpression e = cached_preset("neutral");
  const TriMesh& skin = test::coarse_template_head().skin;
  ASSERT_EQ(e.skin_positions.size(), skin.positions.size());
  for (std::size_t i = 0; i < skin.positions.size(); ++i) ASSERT_EQ(e.skin_positions[i], skin.positions[i]) << i;
  EXPECT_EQ(e.newton_iterations, 0);
}

TEST(FaceExpression, LinearMusclePullsInsertionTowardOriginAndLeavesBackOfHeadStill) {
  const TemplateHead& head = test::coarse_template_head();
  const FaceExpression e = expressions().pose("zyg", {{"zygomaticus_major_L", 1.0}});
  const MuscleLayout* zyg = nullptr;
  for (const MuscleLayout& m : head.muscles) {
    if (m.name == "zygomaticus_major_L") zyg = &m;
  }
  ASSERT_NE(zyg, nullptr);
  const int mid = zyg->fibre_count / 2;
  const Vec3 origin = zyg->grid[static_cast<std::size_t>(mid * zyg->samples_per_fibre)];
  const Vec3 insertion = zyg->grid[static_cast<std::size_t>((mid + 1) * zyg->samples_per_fibre - 1)];
  const auto shaped = shape_muscles({*zyg}, head.skin);
  const Vec3 at = shaped[0].skin_points[static_cast<std::size_t>((mid + 1) * zyg->samples_per_fibre - 1)];
  const Vec3 moved = track(e, {at})[0];
  const Vec3 toward = (origin - insertion).normalized();
  EXPECT_GT((moved - at).dot(toward), 1.0) << "insertion moved " << (moved - at).transpose();
  EXPECT_GT((moved - at).dot(toward), 0.7 * (moved - at).norm());
  // The mirrored insertion on the right moves less; the back of the head stays.
  const Vec3 mirror_at(-at.x(), at.y(), at.z());
  EXPECT_LT((track(e, {mirror_at})[0] - mirror_at).norm(), 0.5 * (moved - at).norm());
  double back = 0.0;
  for (std::size_t i = 0; i < head.skin.positions.size(); ++i) {
    if (head.skin.positions[i].y() > 40.0) back = std::max(back, (e.skin_positions[i] - head.skin.positions[i]).norm());
  }
  EXPECT_LT(back, 0.05 * (moved - at).norm());  // within the Newton tolerance of zero
}

TEST(FaceExpression, SmileRaisesAndWidensMouthCornersSymmetrically) {
  const Vec3 left = skin_landmark("ch'_L"), right = skin_landmark("ch'_R");
  const auto moved = track(cached_preset("smile"), {left, right});
  const Vec3 dl = moved[0] - left, dr = moved[1] - right;
  EXPECT_GT(dl.z(), 1.0);
  EXPECT_GT(dr.z(), 1.0);
  EXPECT_GT(dl.x(), 0.5);   // the left corner moves further left (+x)
  EXPECT_LT(dr.x(), -0.5);  // the right one further right
  // Mirror symmetry of the template: x flips, y and z agree.
  const Vec3 dr_mirrored(-dr.x(), dr.y(), dr.z());
  EXPECT_LT((dl - dr_mirrored).norm(), 0.2 * dl.norm()) << dl.transpose() << " vs " << dr.transpose();
}

TEST(FaceExpression, SphincterNarrowsTheMouth) {
  const Vec3 left = skin_landmark("ch'_L"), right = skin_landmark("ch'_R");
  const auto moved = track(expressions().pose("pucker", {{"orbicularis_oris", 1.0}}), {left, right});
  EXPECT_LT((moved[0] - moved[1]).norm(), (left - right).norm() - 1.0);
}

TEST(FaceExpression, FrownLowersMouthCornersAndSurpriseRaisesTheBrows) {
  const Vec3 corner = skin_landmark("ch'_L");
  EXPECT_LT(track(cached_preset("frown"), {corner})[0].z(), corner.z() - 0.3);
  const TemplateHead& head = test::coarse_template_head();
  const Vec3 brow = head.landmarks[static_cast<std::size_t>(find_template_landmark(head, "g'"))].skin + Vec3(20, 0, 5);
  const Vec3 on_skin = track(cached_preset("neutral"), {brow})[0];
  EXPECT_GT(track(cached_preset("surprise"), {brow})[0].z(), on_skin.z() + 0.5);
}

TEST(FaceExpression, IdenticalAtOneAndFourThreads) {
  const int before = thread_count();
  set_thread_count(1);
  const FaceExpression one = expressions().pose("frown", expression_preset("frown"));
  set_thread_count(4);
  const FaceExpression four = expressions().pose("frown", expression_preset("frown"));
  set_thread_count(before);
  ASSERT_EQ(one.skin_positions.size(), four.skin_positions.size());
  for (std::size_t i = 0; i < one.skin_positions.size(); ++i) ASSERT_EQ(one.skin_positions[i], four.skin_positions[i]);
}

TEST(FaceExpression, RejectsBadActivationsAndNames) {
  const FaceExpressions& e = expressions();
  EXPECT_THROW(e.pose("x", {{"risorius_L", 1.5}}), InputError);
  EXPECT_THROW(e.pose("x", {{"risorius_L", -0.1}}), InputError);
  EXPECT_THROW(e.pose("x", {{"risorius", std::numeric_limits<double>::quiet_NaN()}}), InputError);
  try {
    e.pose("x", {{"zygomaticus_majr", 0.5}});
    ADD_FAILURE() << "no throw";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("did you mean \"zygomaticus_major\""), std::string::npos) << err.what();
  }
  try {
    expression_preset("smiel");
    ADD_FAILURE() << "no throw";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("\"smile\""), std::string::npos) << err.what();
  }
  std::vector<double> wrong(e.model().muscle_names.size(), 0.0);
  wrong[3] = 2.0;
  EXPECT_THROW(e.solver().solve(wrong), InputError);
  EXPECT_THROW(e.solver().solve({0.5}), InputError);
}

TEST(FaceExpression, MorphTargetsHoldDisplacementsAndNames) {
  const TriMesh& skin = test::coarse_template_head().skin;
  const std::vector<FaceExpression> poses = {cached_preset("neutral"), cached_preset("surprise")};
  const std::vector<MorphTarget> targets = expression_morph_targets(skin, poses);
  ASSERT_EQ(targets.size(), 2u);
  EXPECT_EQ(targets[1].name, "surprise");
  double neutral_max = 0.0, surprise_max = 0.0;
  for (std::size_t i = 0; i < skin.positions.size(); ++i) {
    neutral_max = std::max(neutral_max, targets[0].position_deltas[i].norm() + targets[0].normal_deltas[i].norm());
    EXPECT_EQ(targets[1].position_deltas[i], poses[1].skin_positions[i] - skin.positions[i]);
    surprise_max = std::max(surprise_max, targets[1].position_deltas[i].norm());
  }
  EXPECT_EQ(neutral_max, 0.0);
  EXPECT_GT(surprise_max, 1.0);
  FaceExpression bad;
  bad.skin_positions.resize(3);
  EXPECT_THROW(expression_morph_targets(skin, {bad}), InputError);
}

}  // namespace
}  // namespace forensim
