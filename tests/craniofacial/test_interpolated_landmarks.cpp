// Interpolated landmark pairs on the cranium and mandible (paper Figure 6b).
#include "craniofacial/interpolated_landmarks.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>

#include "core/error.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/ray_caster.hpp"
#include "spatial/winding_number.hpp"
#include "template_head_fixture.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;

namespace {

/// The template's landmarks keyed by bone name (ecm2 dropped: it names two pairs).
LandmarkDepths bone_keyed(const TemplateHead& head) {
  LandmarkDepths d;
  for (const TemplateLandmarkPair& p : head.landmarks) {
    if (p.bone_name.rfind("ecm2", 0) == 0) continue;
    d.names.push_back(p.bone_name);
    d.skull.push_back(p.skull);
    d.depth_vectors.push_back(p.skin - p.skull);
  }
  return d;
}

double depth_of(const LandmarkDepths& d, const std::string& name) {
  for (std::size_t i = 0; i < d.names.size(); ++i) {
    if (d.names[i] == name) return d.depth_vectors[i].norm();
  }
  return -1.0;
}

}  // namespace

TEST(InterpolatedLandmarks, LieOnTheOuterSkullWithInterpolatedDepths) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkDepths given = bone_keyed(head);
  const RayCaster rays(head.skull);
  const InterpolatedLandmarks points = interpolate_landmarks(head.skull, rays, given);
  const LandmarkInterpolationOptions defaults;
  const std::size_t cranium = static_cast<std::size_t>(defaults.cranium_rings * defaults.cranium_sectors) + 1;
  std::size_t arcs = 0;
  for (const LandmarkArc& a : defaults.mandible_arcs) arcs += static_cast<std::size_t>(a.count);
  std::string arc_names;
  for (const std::string& n : points.names) arc_names += n.rfind("cranium", 0) == 0 ? "" : n + " ";
  EXPECT_EQ(points.names.size(), cranium + arcs) << "arc points found: " << arc_names;

  const ClosestPointQuery on_skull(head.skull);
  const WindingNumber inside(head.skull);
  const double cranial_lo = std::min({depth_of(given, "g"), depth_of(given, "v"), depth_of(given, "op")});
  const double cranial_hi = std::max({depth_of(given, "g"), depth_of(given, "v"), depth_of(given, "op")});
  for (std::size_t i = 0; i < points.names.size(); ++i) {
    const std::string& name = points.names[i];
    EXPECT_LT(on_skull.query(points.skull[i])->distance, 1e-6) << name;
    EXPECT_NEAR(points.normals[i].norm(), 1.0, 1e-9);
    EXPECT_LT(inside.evaluate(points.skull[i] + 1.5 * points.normals[i]), 0.5) << name << " normal points inward";
    if (name.rfind("cranium", 0) == 0) {
      EXPECT_GE(points.depth_mm[i], cranial_lo - 1e-9) << name;
      EXPECT_LE(points.depth_mm[i], cranial_hi + 1e-9) << name;
      // On the upper part of the cranium: above the zygomatic arches.
      EXPECT_GT(points.skull[i].z(), 10.0) << name;
    } else {
      const std::string from = name.substr(0, name.find('~'));
      const std::string to = name.substr(name.find('~') + 1, name.rfind('_') - name.find('~') - 1);
      const double a = depth_of(given, from), b = depth_of(given, to);
      EXPECT_GE(points.depth_mm[i], std::min(a, b) - 1e-9) << name;
      EXPECT_LE(points.depth_mm[i], std::max(a, b) + 1e-9) << name;
      EXPECT_LT(points.skull[i].z(), -30.0) << name << " on the mandible";
    }
  }
}

TEST(InterpolatedLandmarks, MoveWithTheSkullUnderASimilarity) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkDepths given = bone_keyed(head);
  const Mat3 r = (Eigen::AngleAxisd(0.3, Vec3(0.2, 1.0, 0.4).normalized())).toRotationMatrix();
  const double s = 0.92;
  const Vec3 t(-15, 30, 8);
  TriMesh skull = head.skull;
  for (Vec3& p : skull.positions) p = s * r * p + t;
  LandmarkDepths moved = given;
  for (std::size_t i = 0; i < moved.names.size(); ++i) {
    moved.skull[i] = s * r * moved.skull[i] + t;
    moved.depth_vectors[i] = s * r * moved.depth_vectors[i];
  }
  for (Vec3& n : skull.normals) n = r * n;
  const InterpolatedLandmarks a = interpolate_landmarks(head.skull, RayCaster(head.skull), given);
  const InterpolatedLandmarks b = interpolate_landmarks(skull, RayCaster(skull), moved);
  ASSERT_EQ(a.names, b.names);
  for (std::size_t i = 0; i < a.names.size(); ++i) {
    EXPECT_LT((s * r * a.skull[i] + t - b.skull[i]).norm(), 1e-3) << a.names[i];
    EXPECT_NEAR(s * a.depth_mm[i], b.depth_mm[i], 1e-6) << a.names[i];
    EXPECT_LT((r * a.normals[i] - b.normals[i]).norm(), 1e-6) << a.names[i];
  }
}

TEST(InterpolatedLandmarks, SkipsWhatTheLandmarksDoNotSupport) {
  const TemplateHead& head = coarse_template_head();
  LandmarkDepths given = bone_keyed(head);
  const RayCaster rays(head.skull);
  LandmarkInterpolationOptions no_mandible;
  no_mandible.mandible = false;
  const InterpolatedLandmarks cranium_only = interpolate_landmarks(head.skull, rays, given, no_mandible);
  for (const std::string& n : cranium_only.names) EXPECT_EQ(n.rfind("cranium", 0), 0u) << n;
  // Without vertex there is no head frame: no cranium points.
  for (std::size_t i = 0; i < given.names.size(); ++i) {
    if (given.names[i] == "v") given.names[i] = "unused";
  }
  for (const std::string& n : interpolate_landmarks(head.skull, rays, given).names)
    EXPECT_NE(n.rfind("cranium", 0), 0u) << n;
  LandmarkInterpolationOptions bad;
  bad.cranium_rings = 0;
  EXPECT_THROW(interpolate_landmarks(head.skull, rays, given, bad), InputError);
  LandmarkDepths ragged = given;
  ragged.depth_vectors.pop_back();
  EXPECT_THROW(interpolate_landmarks(head.skull, rays, ragged), InputError);
}
