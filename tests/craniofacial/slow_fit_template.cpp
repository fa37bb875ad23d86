// End-to-end fitting on the full-resolution template head: a skull that differs from the template's where
// no landmark is (a wider, higher vault and a longer mandible) pierces the skin after the warp with the given
// landmarks only, and no longer after the interpolated landmarks (paper Figure 6a to 6b).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "craniofacial/fit_template.hpp"
#include "craniofacial/template_head.hpp"
#include "geometry/mesh_topology.hpp"

using namespace forensim;

namespace {

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// A smooth non-affine change of the head: the parietal vault widens by up to 9 % and rises, the mandible
/// body lengthens forward.
Vec3 deform(const Vec3& p) {
  const double vault = smoothstep(20.0, 90.0, p.z());
  const double jaw = smoothstep(-30.0, -60.0, p.z()) * smoothstep(-20.0, -70.0, p.y());
  return Vec3(p.x() * (1.0 + 0.09 * vault), p.y() - 4.0 * jaw, p.z() + 5.0 * vault * smoothstep(40.0, 120.0, p.z()));
}

const TemplateHead& full_head() {
  static const TemplateHead head = make_template_head();
  return head;
}

}  // namespace

TEST(SlowFitTemplate, FullTemplateHeadIsClosedAndTextured) {
  const TemplateHead& head = full_head();
  std::cout << "template: " << head.skin.triangles.size() << " skin triangles, " << head.skull.triangles.size()
            << " skull triangles, UV L2 stretch " << head.uv_l2_stretch << ", built in " << head.seconds << " s\n";
  EXPECT_TRUE(check_topology(head.skin).is_closed());
  EXPECT_TRUE(head.uv_overlap_free);
  EXPECT_EQ(head.landmarks.size(), 36u);
  EXPECT_EQ(head.muscles.size(), 24u);
}

TEST(SlowFitTemplate, InterpolatedLandmarksRemoveSkullSkinViolations) {
  const TemplateHead& head = full_head();
  TriMesh skull = head.skull;
  for (Vec3& p : skull.positions) p = deform(p);
  LandmarkDepths landmarks;
  for (const TemplateLandmarkPair& p : head.landmarks) {
    landmarks.names.push_back(p.skin_name);
    landmarks.skull.push_back(deform(p.skull));
    // The template's own tissue depth along the deformed skull's direction there.
    landmarks.depth_vectors.push_back((deform(p.skull + p.skull_normal) - deform(p.skull)).normalized() * p.depth_mm);
  }
  const TemplateFitResult fit = fit_template(head, skull, landmarks);
  std::cout << "violations with the " << fit.given_pair_count
            << " given pairs: " << fit.violations_given_only.skull_outside_skin
            << " skull vertices outside the skin (max " << fit.violations_given_only.max_skull_protrusion_mm << " mm), "
            << fit.violations_given_only.skin_inside_skull << " skin vertices inside the skull; with "
            << fit.interpolated.names.size() << " interpolated pairs: " << fit.violations.skull_outside_skin << " (max "
            << fit.violations.max_skull_protrusion_mm << " mm), " << fit.violations.skin_inside_skull << "; fit "
            << fit.seconds_total << " s\n";
  EXPECT_GT(fit.violations_given_only.total(), 0u);
  // The interpolated pairs alone remove them here (no correction pair needed), and the final fit has none.
  EXPECT_EQ(fit.violations_before_correction.total(), 0u);
  EXPECT_TRUE(fit.corrections.sources.empty());
  EXPECT_EQ(fit.violations.total(), 0u);
  EXPECT_LT(fit.max_landmark_residual_mm, 1e-9 * 250.0);
}
