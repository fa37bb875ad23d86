// The uncertainty ensemble: new depths re-target the warp exactly as a fresh reconstruction; the spread
// scales with the SDs (the head is affine in the depths) and vanishes without them; the same at any thread
// count.
#include "craniofacial/reconstruction_uncertainty.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/template_landmark_detection.hpp"
#include "template_head_fixture.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;

namespace {

constexpr double head_mm = 250.0;

ReconstructionOptions quick_options() {
  ReconstructionOptions o;
  o.fit.count_violations = false;
  // Updates keep the pair set; a fresh fit would look for correction pairs anew (test_violation_correction.cpp
  // checks that updates keep the corrections' targets).
  o.fit.correction.rounds = 0;
  return o;
}

/// The default table's depths with every SD multiplied by `k`.
TissueDepths scaled_sd(double k) {
  TissueDepths d = select_tissue_depths(built_in_tissue_depth_table("ttable_2023"));
  for (TissueDepthEntry& e : d.entries) {
    if (e.sd_mm) *e.sd_mm *= k;
  }
  return d;
}

}  // namespace

TEST(ReconstructionUncertainty, NewDepthsEqualAFreshReconstruction) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  const TissueDepths depths = scaled_sd(1.0);
  Reconstruction r(head, head.skull, landmarks, depths, quick_options());
  const TissueDepths obese = offset_by_sd(depths, 1.0);
  EXPECT_GT(r.set_depths(obese), 0u);
  const Reconstruction fresh(head, head.skull, landmarks, obese, quick_options());
  double worst = 0.0;
  for (std::size_t v = 0; v < fresh.result().skin.positions.size(); ++v) {
    worst = std::max(worst, (r.result().skin.positions[v] - fresh.result().skin.positions[v]).norm());
  }
  EXPECT_LT(worst, 1e-9 * head_mm);
  for (const DepthVector& v : r.result().depth_vectors.vectors) {
    EXPECT_NEAR(v.depth_mm, *obese.depth_mm(v.bone_landmark), 1e-12) << v.bone_landmark;
  }
}

TEST(ReconstructionUncertainty, SpreadScalesWithTheSdsAndVanishesWithout) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  // Small SDs, so no draw is truncated at zero depth and the head stays affine in the SDs.
  Reconstruction narrow(head, head.skull, landmarks, scaled_sd(0.2), quick_options());
  Reconstruction wide(head, head.skull, landmarks, scaled_sd(0.4), quick_options());
  Reconstruction none(head, head.skull, landmarks, scaled_sd(0.0), quick_options());
  const ReconstructionUncertainty a = reconstruction_uncertainty(narrow, 4, 7);
  const ReconstructionUncertainty b = reconstruction_uncertainty(wide, 4, 7);
  const ReconstructionUncertainty z = reconstruction_uncertainty(none, 4, 7);
  ASSERT_EQ(a.vertex_spread_mm.size(), head.skin.positions.size());
  EXPECT_GT(a.max_spread_mm, 0.05);
  for (std::size_t v = 0; v < a.vertex_spread_mm.size(); ++v) {
    ASSERT_NEAR(b.vertex_spread_mm[v], 2.0 * a.vertex_spread_mm[v], 1e-6) << v;
    ASSERT_LT(z.vertex_spread_mm[v], 1e-9);
  }
  // The reconstruction is left at its own depths.
  const Reconstruction fresh(head, head.skull, landmarks, scaled_sd(0.2), quick_options());
  for (std::size_t v = 0; v < fresh.result().skin.positions.size(); ++v) {
    ASSERT_LT((narrow.result().skin.positions[v] - fresh.result().skin.positions[v]).norm(), 1e-9 * head_mm);
  }
  EXPECT_THROW(reconstruction_uncertainty(narrow, 1, 7), InputError);
}

TEST(ReconstructionUncertainty, SameSpreadAtAnyThreadCount) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  Reconstruction r(head, head.skull, landmarks, scaled_sd(1.0), quick_options());
  set_thread_count(1);
  const ReconstructionUncertainty one = reconstruction_uncertainty(r, 3, 11);
  set_thread_count(3);
  const ReconstructionUncertainty three = reconstruction_uncertainty(r, 3, 11);
  set_thread_count(0);
  EXPECT_EQ(one.vertex_spread_mm, three.vertex_spread_mm);
  EXPECT_EQ(one.max_spread_mm, three.max_spread_mm);
}
