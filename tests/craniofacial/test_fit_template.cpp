// Fitting the template head to a skull (eq. 1 on the template's skin and muscle grids).
#include "craniofacial/fit_template.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "template_head_fixture.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;
using forensim::test::template_landmark_depths;

namespace {

constexpr double head_mm = 250.0;

double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

TriMesh transformed(const TriMesh& mesh, const Mat3& a, const Vec3& t) {
  TriMesh out = mesh;
  for (Vec3& p : out.positions) p = a * p + t;
  return out;
}

FitTemplateOptions given_only() {
  FitTemplateOptions o;
  o.interpolated_landmarks = false;
  o.count_violations = false;
  return o;
}

}  // namespace

TEST(FitTemplate, OntoItsOwnLandmarksIsTheIdentity) {
  const TemplateHead& head = coarse_template_head();
  const TemplateFitResult fit = fit_template(head, head.skull, template_landmark_depths(head), given_only());
  EXPECT_EQ(fit.given_pair_count, head.landmarks.size());
  EXPECT_LT(max_distance(fit.skin.positions, head.skin.positions), 1e-9 * head_mm);
  ASSERT_EQ(fit.muscle_layouts.size(), head.muscles.size());
  for (std::size_t m = 0; m < head.muscles.size(); ++m) {
    EXPECT_LT(max_distance(fit.muscle_layouts[m].grid, head.muscles[m].grid), 1e-9 * head_mm);
  }
  // Topology and UVs are the template's.
  EXPECT_EQ(fit.skin.triangles, head.skin.triangles);
  EXPECT_EQ(fit.skin.triangle_uvs, head.skin.triangle_uvs);
  EXPECT_EQ(fit.skin.uvs, head.skin.uvs);
}

TEST(FitTemplate, ReproducesAnAffineSkullMapOnTheWholeHead) {
  const TemplateHead& head = coarse_template_head();
  Mat3 a;
  a << 1.08, 0.03, 0.0, -0.02, 0.95, 0.04, 0.01, 0.0, 1.12;
  const Vec3 t(4.0, -7.0, 12.0);
  LandmarkDepths l = template_landmark_depths(head);
  for (std::size_t i = 0; i < l.names.size(); ++i) {
    l.skull[i] = a * l.skull[i] + t;
    l.depth_vectors[i] = a * l.depth_vectors[i];
  }
  const TemplateFitResult fit = fit_template(head, transformed(head.skull, a, t), l, given_only());
  std::vector<Vec3> expected;
  for (const Vec3& p : head.skin.positions) expected.push_back(a * p + t);
  EXPECT_LT(max_distance(fit.skin.positions, expected), 1e-9 * head_mm);
  EXPECT_LT(fit.max_landmark_residual_mm, 1e-9 * head_mm);
  // The muscles keep their place on the skin: their shapes lie under the warped skin.
  for (const MuscleShape& m : fit.muscles) {
    for (std::size_t i = 0; i < m.skin_points.size(); ++i) {
      ASSERT_LT((m.skin_points[i] - m.fibre_points[i]).norm(), 5.0) << m.name;
    }
  }
}

TEST(FitTemplate, TargetsAreSkullPlusDepthVectors) {
  const TemplateHead& head = coarse_template_head();
  LandmarkDepths l = template_landmark_depths(head);
  for (std::size_t i = 0; i < l.names.size(); ++i) l.depth_vectors[i] *= 1.3;  // an obese build, say
  FitTemplateOptions o = given_only();
  o.interpolated_landmarks = true;
  const TemplateFitResult fit = fit_template(head, head.skull, l, o);
  for (std::size_t i = 0; i < fit.given_pair_count; ++i) {
    EXPECT_LT((fit.targets[i] - (l.skull[i] + l.depth_vectors[i])).norm(), 1e-12);
  }
  EXPECT_GT(fit.targets.size(), fit.given_pair_count);  // interpolated pairs were added
  EXPECT_EQ(fit.interpolated.names.size(), fit.targets.size() - fit.given_pair_count);
  EXPECT_LT(fit.max_landmark_residual_mm, 1e-9 * head_mm);
}

TEST(FitTemplate, MovingOneLandmarkMatchesAFreshFit) {
  const TemplateHead& head = coarse_template_head();
  LandmarkDepths l = template_landmark_depths(head);
  FitTemplateOptions o;
  o.count_violations = false;
  TemplateFit fit(head, head.skull, l, o);
  // Move pogonion forward by 4 mm and give it 2 mm more tissue.
  std::size_t pg = 0;
  while (l.names[pg] != "pg'") ++pg;
  const Vec3 moved = l.skull[pg] + Vec3(0, -4, 0);
  const Vec3 depth = l.depth_vectors[pg] * (1.0 + 2.0 / l.depth_vectors[pg].norm());
  const std::size_t changed = fit.move_landmark("pg'", moved, depth);
  EXPECT_GE(changed, 1u);
  l.skull[pg] = moved;
  l.depth_vectors[pg] = depth;
  const TemplateFitResult fresh = fit_template(head, head.skull, l, o);
  ASSERT_EQ(fresh.targets.size(), fit.result().targets.size());
  EXPECT_LT(max_distance(fit.result().skin.positions, fresh.skin.positions), 1e-7 * head_mm);
  EXPECT_LT(fit.result().max_landmark_residual_mm, 1e-9 * head_mm);
  EXPECT_THROW(fit.move_landmark("not-a-landmark", moved, depth), InputError);
}

TEST(FitTemplate, RejectsBadLandmarks) {
  const TemplateHead& head = coarse_template_head();
  LandmarkDepths l = template_landmark_depths(head);
  LandmarkDepths unknown = l;
  unknown.names[0] = "xx";
  EXPECT_THROW(fit_template(head, head.skull, unknown, given_only()), InputError);
  LandmarkDepths twice = l;
  twice.names[1] = twice.names[0];
  EXPECT_THROW(fit_template(head, head.skull, twice, given_only()), InputError);
  LandmarkDepths nan = l;
  nan.depth_vectors[3].x() = std::nan("");
  EXPECT_THROW(fit_template(head, head.skull, nan, given_only()), InputError);
  LandmarkDepths few;
  for (int i = 0; i < 3; ++i) {
    few.names.push_back(l.names[static_cast<std::size_t>(i)]);
    few.skull.push_back(l.skull[static_cast<std::size_t>(i)]);
    few.depth_vectors.push_back(l.depth_vectors[static_cast<std::size_t>(i)]);
  }
  EXPECT_THROW(fit_template(head, head.skull, few, given_only()), InputError);
  LandmarkDepths ragged = l;
  ragged.skull.pop_back();
  EXPECT_THROW(fit_template(head, head.skull, ragged, given_only()), InputError);
}
