// Correction pairs at skull/skin violations: a skull with a bump that the given landmarks miss pierces the
// warped skin; the correction rounds cover it at the neighbouring landmarks' depth.
#include "craniofacial/violation_correction.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "craniofacial/fit_template.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "spatial/ray_caster.hpp"

using namespace forensim;

namespace {

const Vec3 kBumpDirection = Vec3(1.0, 1.0, 1.0).normalized();
constexpr double kSkullRadius = 50.0, kBumpHeight = 12.0, kDepth = 5.0;

/// A template of two spheres (skin 60 mm, skull 50 mm) with landmark pairs on the six axes.
TemplateHead sphere_template() {
  TemplateHead head;
  head.skin = make_icosphere(Vec3::Zero(), 60.0, 4);
  compute_normals(head.skin);
  head.skull = make_icosphere(Vec3::Zero(), kSkullRadius, 3);
  compute_normals(head.skull);
  for (int k = 0; k < 6; ++k) {
    Vec3 d = Vec3::Zero();
    d(k / 2) = k % 2 == 0 ? 1.0 : -1.0;
    TemplateLandmarkPair p;
    p.bone_name = "axis" + std::to_string(k);
    p.skin_name = p.bone_name + "'";
    p.skull = kSkullRadius * d;
    p.skull_normal = d;
    p.skin = 60.0 * d;
    p.depth_mm = 10.0;
    head.landmarks.push_back(p);
  }
  return head;
}

/// The target skull: the 50 mm sphere with a smooth 12 mm bump around (1, 1, 1), 55 degrees from every axis.
TriMesh bumpy_skull() {
  TriMesh skull = make_icosphere(Vec3::Zero(), kSkullRadius, 5);
  for (Vec3& p : skull.positions) {
    const double angle = std::acos(std::clamp(p.normalized().dot(kBumpDirection), -1.0, 1.0));
    const double t = std::max(0.0, 1.0 - (angle / 0.6) * (angle / 0.6));  // flat at its top
    p *= (kSkullRadius + kBumpHeight * t * t) / kSkullRadius;
  }
  compute_normals(skull);
  return skull;
}

/// Landmarks on the target's axes with 5 mm depth vectors.
LandmarkDepths axis_landmarks(const TemplateHead& head) {
  LandmarkDepths l;
  for (const TemplateLandmarkPair& p : head.landmarks) {
    l.names.push_back(p.skin_name);
    l.skull.push_back(p.skull);
    l.depth_vectors.push_back(kDepth * p.skull_normal);
  }
  return l;
}

FitTemplateOptions sphere_options(int rounds) {
  FitTemplateOptions o;
  o.interpolated_landmarks = false;
  o.muscles = false;
  o.count_violations = true;
  o.correction.rounds = rounds;
  return o;
}

}  // namespace

TEST(ViolationCorrection, BumpThatPiercesTheSkinIsCoveredAtTheNeighboursDepth) {
  const TemplateHead head = sphere_template();
  const TriMesh skull = bumpy_skull();
  // Without corrections the warp is the uniform scaling 55 / 60 (eq. 1 reproduces affine maps): the bump's top,
  // 62 mm out, pierces the 55 mm skin.
  const TemplateFitResult plain = fit_template(head, skull, axis_landmarks(head), sphere_options(0));
  ASSERT_GT(plain.violations.skull_outside_skin, 0u);
  std::size_t apex = 0;
  for (std::size_t v = 0; v < skull.positions.size(); ++v)
    if (skull.positions[v].norm() > skull.positions[apex].norm()) apex = v;
  const double apex_mm = skull.positions[apex].norm();
  EXPECT_NEAR(plain.violations.max_skull_protrusion_mm, apex_mm - kSkullRadius - kDepth, 0.1);
  EXPECT_TRUE(plain.corrections.sources.empty());

  const TemplateFitResult fit = fit_template(head, skull, axis_landmarks(head), sphere_options(6));
  EXPECT_EQ(fit.violations_before_correction.skull_outside_skin, plain.violations.skull_outside_skin);
  EXPECT_EQ(fit.violations.total(), 0u);
  ASSERT_GT(fit.corrections.sources.size(), 0u);
  EXPECT_GE(fit.correction_rounds, 1);
  EXPECT_EQ(fit.targets.size(), fit.given_pair_count + fit.corrections.sources.size());
  // Every correction takes the landmarks' depth (all are 5 mm) and the warp interpolates its target.
  for (std::size_t j = 0; j < fit.corrections.sources.size(); ++j)
    EXPECT_DOUBLE_EQ(fit.corrections.depth_mm[j], kDepth);
  EXPECT_LT(fit.max_landmark_residual_mm, 1e-6);
  // Over the bump's top the skin stands one depth off the bone (the deepest violation is taken first).
  const RayCaster skin_rays(fit.skin);
  const auto hit = skin_rays.intersect(Vec3::Zero(), skull.positions[apex].normalized(), 0.0, 200.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, apex_mm + kDepth, 0.5);
  // Far from the bump the skin is untouched by the corrections: still the scaled sphere.
  const auto side = skin_rays.intersect(Vec3::Zero(), -kBumpDirection, 0.0, 200.0);
  ASSERT_TRUE(side.has_value());
  EXPECT_NEAR(side->t, kSkullRadius + kDepth, 1.0);
}

TEST(ViolationCorrection, MovingALandmarkKeepsTheCorrectionsAndReadsTheirDepthAgain) {
  const TemplateHead head = sphere_template();
  const TriMesh skull = bumpy_skull();
  TemplateFit fit(head, skull, axis_landmarks(head), sphere_options(6));
  const std::size_t pairs = fit.result().targets.size();
  ASSERT_GT(fit.result().corrections.sources.size(), 0u);
  // Thicker tissue at every landmark: the corrections' depths follow (same pairs, no new factorisation).
  LandmarkDepths thick = axis_landmarks(head);
  for (Vec3& d : thick.depth_vectors) d *= 1.4;
  fit.set_landmarks(thick.skull, thick.depth_vectors);
  EXPECT_EQ(fit.result().targets.size(), pairs);
  for (const double d : fit.result().corrections.depth_mm) EXPECT_DOUBLE_EQ(d, 1.4 * kDepth);
  // The same head as a fit that starts with those pairs: every pair interpolated exactly.
  EXPECT_LT(fit.result().max_landmark_residual_mm, 1e-6);
  const std::vector<Vec3> targets = fit.result().corrections.targets();
  for (std::size_t j = 0; j < targets.size(); ++j) {
    const std::size_t k = fit.result().given_pair_count + j;
    EXPECT_LT((fit.result().targets[k] - targets[j]).norm(), 1e-12);
  }
  fit.recount_violations();
  EXPECT_EQ(fit.result().violations.total(), 0u);
}

TEST(ViolationCorrection, DepthIsTheThinnestNeighbour) {
  const std::vector<Vec3> depth_vectors = {Vec3(0, 0, 7), Vec3(3, 4, 0), Vec3(0, 9, 0)};
  EXPECT_DOUBLE_EQ(correction_depth({0, 1, 2}, depth_vectors), 5.0);
  EXPECT_DOUBLE_EQ(correction_depth({2, 0}, depth_vectors), 7.0);
  EXPECT_THROW(correction_depth({}, depth_vectors), InputError);
  EXPECT_THROW(correction_depth({3}, depth_vectors), InputError);
}

TEST(ViolationCorrection, PairsKeepTheirSpacingAndRejectBadInput) {
  const TemplateHead head = sphere_template();
  const TriMesh skull = bumpy_skull();
  const TemplateFitResult plain = fit_template(head, skull, axis_landmarks(head), sphere_options(0));
  const LandmarkDepths l = axis_landmarks(head);
  ViolationCorrectionOptions o;
  o.spacing_mm = 4.0;
  o.max_pairs = 1000;
  const ViolationCorrectionPairs a = violation_correction_pairs(skull, head.skin, plain.skin, plain.violations, l.skull,
                                                                l.depth_vectors, plain.sources, plain.targets, o);
  ASSERT_GT(a.sources.size(), 1u);
  for (std::size_t i = 0; i < a.sources.size(); ++i) {
    for (std::size_t j = i + 1; j < a.sources.size(); ++j) EXPECT_GE((a.sources[i] - a.sources[j]).norm(), 4.0);
    // Each target stands outside the skull along its outward normal.
    EXPECT_GT(a.normals[i].dot(a.skull[i]), 0.0);
    EXPECT_EQ(a.neighbours[i].size(), 3u);
  }
  // The first pair is the deepest violation: the bump's top.
  EXPECT_GT(a.skull[0].normalized().dot(kBumpDirection), 0.999);
  // Deterministic.
  const ViolationCorrectionPairs b = violation_correction_pairs(skull, head.skin, plain.skin, plain.violations, l.skull,
                                                                l.depth_vectors, plain.sources, plain.targets, o);
  EXPECT_EQ(a.sources, b.sources);
  o.spacing_mm = 0.0;
  EXPECT_THROW(violation_correction_pairs(skull, head.skin, plain.skin, plain.violations, l.skull, l.depth_vectors,
                                          plain.sources, plain.targets, o),
               InputError);
  TriMesh no_normals = skull;
  no_normals.normals.clear();
  EXPECT_THROW(violation_correction_pairs(no_normals, head.skin, plain.skin, plain.violations, l.skull, l.depth_vectors,
                                          plain.sources, plain.targets),
               InputError);
}
