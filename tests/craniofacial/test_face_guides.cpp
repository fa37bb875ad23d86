// The nose and mouth guides and the second warp (paper section 4.3).
#include "craniofacial/face_guides.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "template_head_fixture.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;
using forensim::test::template_landmark_depths;

namespace {

const TemplateFitResult& self_fit() {
  static const TemplateFitResult fit = [] {
    FitTemplateOptions o;
    o.count_violations = false;
    return fit_template(coarse_template_head(), coarse_template_head().skull,
                        template_landmark_depths(coarse_template_head()), o);
  }();
  return fit;
}

Vec3 skin_landmark(const GuidedHead& g, const std::string& name) {
  for (const TemplateSkinLandmark& l : g.skin_landmarks) {
    if (l.name == name) return l.position;
  }
  ADD_FAILURE() << "no " << name;
  return Vec3::Zero();
}

Vec3 skin_landmark(const TemplateFitResult& f, const std::string& name) {
  for (const TemplateSkinLandmark& l : f.skin_landmarks) {
    if (l.name == name) return l.position;
  }
  ADD_FAILURE() << "no " << name;
  return Vec3::Zero();
}

}  // namespace

TEST(FaceGuides, TemplateCarriesTheNoseAndMouthSkinLandmarks) {
  const TemplateHead& head = coarse_template_head();
  ASSERT_EQ(head.skin_landmarks.size(), 6u);
  const TemplateFitResult& fit = self_fit();
  const Vec3 prn = skin_landmark(fit, "prn'"), al = skin_landmark(fit, "al'_L"), sto = skin_landmark(fit, "sto'");
  // Pronasale in front of everything else on the face; the ala lateral of it; stomion below the nose.
  for (const Vec3& p : head.skin.positions) ASSERT_GE(p.y(), prn.y() - 0.5);
  EXPECT_GT(al.x(), 8.0);
  EXPECT_LT(sto.z(), prn.z() - 15.0);
  EXPECT_LT(std::abs(prn.x()), 1.0);
}

TEST(FaceGuides, NoGuidesChangeNothing) {
  const GuidedHead g = apply_face_guides(coarse_template_head(), self_fit(), FaceGuides{});
  EXPECT_TRUE(g.adjusted.empty());
  for (std::size_t v = 0; v < g.skin.positions.size(); ++v) {
    ASSERT_LT((g.skin.positions[v] - self_fit().skin.positions[v]).norm(), 1e-9 * 250.0);
  }
}

TEST(FaceGuides, NoseWidthAndTipFollowTheRules) {
  const TemplateFitResult& fit = self_fit();
  FaceGuides guides;
  guides.nasal_aperture_left_mm = 12.0;
  guides.nasal_aperture_right_mm = -12.0;
  guides.nasal_spine_base = Vec3(0, -74, -14);
  guides.nasal_spine_tip = Vec3(0, -80, -15);  // 6.08 mm long, pointing forward and slightly down
  const GuidedHead g = apply_face_guides(coarse_template_head(), fit, guides);
  EXPECT_EQ(g.adjusted.size(), 3u);
  EXPECT_NEAR(skin_landmark(g, "al'_L").x(), 17.0, 1e-7);
  EXPECT_NEAR(skin_landmark(g, "al'_R").x(), -17.0, 1e-7);
  // Krogman: on the spine's line, three spine lengths in front of the mid-philtrum marker.
  const Vec3 base = *guides.nasal_spine_base, tip = *guides.nasal_spine_tip;
  const Vec3 prn = skin_landmark(g, "prn'");
  const Vec3 u = (tip - base).normalized();
  EXPECT_LT(((prn - tip) - (prn - tip).dot(u) * u).norm(), 1e-7);
  std::size_t mp = 0;
  while (fit.pair_names[mp] != "mp'") ++mp;
  EXPECT_NEAR(-prn.y(), -fit.targets[mp].y() + 3.0 * (tip - base).norm(), 1e-7);
  // Every other landmark stays where the first fit put it (the second warp interpolates them).
  EXPECT_LT(g.max_landmark_residual_mm, 1e-9 * 250.0);
  // Skin far from the nose hardly moves.
  for (std::size_t v = 0; v < g.skin.positions.size(); ++v) {
    const double moved = (g.skin.positions[v] - fit.skin.positions[v]).norm();
    if (moved > 1.0) {
      ASSERT_LT((fit.skin.positions[v] - skin_landmark(fit, "prn'")).norm(), 60.0) << "vertex " << v;
    }
  }
}

TEST(FaceGuides, MouthCornersAndLipsTakeTheirGuides) {
  FaceGuides guides;
  guides.mouth_corner_left_mm = 24.0;
  guides.mouth_corner_right_mm = -23.0;
  guides.lip_parting_mm = -42.0;
  guides.upper_lip_border_mm = -32.0;
  guides.lower_lip_border_mm = -52.0;
  const GuidedHead g = apply_face_guides(coarse_template_head(), self_fit(), guides);
  EXPECT_NEAR(skin_landmark(g, "ch'_L").x(), 24.0, 1e-7);
  EXPECT_NEAR(skin_landmark(g, "ch'_R").x(), -23.0, 1e-7);
  for (const char* n : {"ch'_L", "ch'_R", "sto'"}) EXPECT_NEAR(skin_landmark(g, n).z(), -42.0, 1e-7) << n;
  for (std::size_t i = 0; i < g.adjusted.size(); ++i) {
    if (g.adjusted[i] == "ls'") {
      EXPECT_NEAR(g.adjusted_to[i].z(), -32.0, 1e-12);
    }
    if (g.adjusted[i] == "li'") {
      EXPECT_NEAR(g.adjusted_to[i].z(), -52.0, 1e-12);
    }
  }
  EXPECT_EQ(g.adjusted.size(), 5u);
  EXPECT_EQ(g.muscles.size(), 24u);
}

TEST(FaceGuides, RejectsBadGuides) {
  FaceGuides spine_backwards;
  spine_backwards.nasal_spine_base = Vec3(0, -80, -15);
  spine_backwards.nasal_spine_tip = Vec3(0, -74, -14);
  EXPECT_THROW(apply_face_guides(coarse_template_head(), self_fit(), spine_backwards), InputError);
  FaceGuides half_spine;
  half_spine.nasal_spine_tip = Vec3(0, -80, -15);
  EXPECT_THROW(apply_face_guides(coarse_template_head(), self_fit(), half_spine), InputError);
  FaceGuides nan;
  nan.lip_parting_mm = std::nan("");
  EXPECT_THROW(apply_face_guides(coarse_template_head(), self_fit(), nan), InputError);
  FaceGuides skew;
  skew.up = Vec3(0.5, 0, 1).normalized();
  EXPECT_THROW(apply_face_guides(coarse_template_head(), self_fit(), skew), InputError);
}
