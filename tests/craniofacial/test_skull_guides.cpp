// Nose and mouth guides measured on the skull: the nasal aperture's edges on the built-in skull agree with
// the phantom's carved aperture; the spine length and mouth corners follow their definitions; given guides override.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "craniofacial/face_guides_job.hpp"
#include "craniofacial/skull_guides.hpp"
#include "template_head_fixture.hpp"

namespace forensim {
namespace {

LandmarkSet template_skull_landmarks(const TemplateHead& head) {
  LandmarkSet set("template skull");
  for (const TemplateLandmarkPair& p : head.landmarks)
    if (!set.contains(p.bone_name)) set.add({p.bone_name, p.skull});  // ecm2 pairs twice (two skin points)
  return set;
}

TEST(SkullGuides, ApertureEdgesMatchThePhantomsApertureAndTheMouthFollowsTheCanines) {
  const TemplateHead& head = test::coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  const SkullGuideMeasurement m = measure_skull_guides(head.skull, landmarks);
  EXPECT_FALSE(m.head_frame);  // no porions in the template's pairs: LPS axes
  ASSERT_TRUE(m.guides.nasal_aperture_left_mm && m.guides.nasal_aperture_right_mm)
      << (m.missing.empty() ? "" : m.missing.front());
  // The head phantom carves the aperture into the maxilla's front (y = -78) as an ellipsoid centred at
  // (0, -80, -4) with radii (11, 14, 14): its rim on that plane lies at x = 11 sqrt(1 - (2/14)^2) = 10.9 mm
  // on the widest line, z = -4 (the skull is meshed from 3 mm voxels here, with a 3 mm blend at the rim).
  EXPECT_NEAR(*m.guides.nasal_aperture_left_mm, 10.9, 1.5);
  EXPECT_NEAR(*m.guides.nasal_aperture_right_mm, -10.9, 1.5);
  EXPECT_NEAR(*m.guides.nasal_aperture_left_mm, -*m.guides.nasal_aperture_right_mm, 1.0);  // symmetric phantom
  EXPECT_NEAR(m.aperture_height_mm, -4.0, 4.0);
  ASSERT_TRUE(m.guides.mouth_corner_left_mm && m.guides.mouth_corner_right_mm);
  // The canine eminences: where the phantom's alveolar bone turns from facing forward to facing sideways (its
  // normal at 45 degrees), lateral of the phantom's supra-canine points, which lie over its narrow arch of teeth
  // (x = 24 sin a: the canine at 9.8 mm) inside a wider bone. The mouth corners lie half a canine's width (3.75 mm)
  // lateral of them.
  ASSERT_TRUE(m.canine_left_mm && m.canine_right_mm);
  EXPECT_GT(m.canine_left_mm->x(), landmarks.at("sC_L").position_mm.x());
  EXPECT_LT(m.canine_left_mm->x(), 30.0);
  EXPECT_NEAR(m.canine_left_mm->x(), -m.canine_right_mm->x(), 1.5);  // symmetric phantom
  EXPECT_NEAR(m.canine_left_mm->z(), landmarks.at("sC_L").position_mm.z(), 4.0 + 1e-9);
  EXPECT_DOUBLE_EQ(*m.guides.mouth_corner_left_mm, m.canine_left_mm->x() + 3.75);
  EXPECT_DOUBLE_EQ(*m.guides.mouth_corner_right_mm, m.canine_right_mm->x() - 3.75);
  EXPECT_FALSE(m.guides.nasal_spine_tip.has_value());  // no ans among the template's pairs
  ASSERT_EQ(m.missing.size(), 1u);
  EXPECT_NE(m.missing[0].find("nasal_spine"), std::string::npos);
}

TEST(SkullGuides, ApertureIsFoundUpToNasionWhenRhinionLiesOnTheMaxillaBelowIt) {
  // A scan too coarse for the nasal bones puts rhinion on the maxilla just above subspinale: no line below it
  // opens, and the lines up to nasion find the same widest line as with the phantom's own rhinion.
  const TemplateHead& head = test::coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  const SkullGuideMeasurement reference = measure_skull_guides(head.skull, landmarks);
  ASSERT_TRUE(reference.guides.nasal_aperture_left_mm.has_value());
  LandmarkSet low("low rhinion");
  for (const Landmark& l : landmarks.landmarks()) {
    low.add({l.name, l.name == "rhi" ? Vec3(landmarks.at("ss").position_mm + Vec3(0.0, 0.0, 1.0)) : l.position_mm});
  }
  const SkullGuideMeasurement m = measure_skull_guides(head.skull, low);
  ASSERT_TRUE(m.guides.nasal_aperture_left_mm && m.guides.nasal_aperture_right_mm)
      << (m.missing.empty() ? "" : m.missing.front());
  EXPECT_NEAR(*m.guides.nasal_aperture_left_mm, *reference.guides.nasal_aperture_left_mm, 0.5);
  EXPECT_NEAR(*m.guides.nasal_aperture_right_mm, *reference.guides.nasal_aperture_right_mm, 0.5);
  // Without nasion as well, nothing opens below the low rhinion.
  LandmarkSet no_nasion("no nasion");
  for (const Landmark& l : low.landmarks()) {
    if (l.name != "n") no_nasion.add(l);
  }
  const SkullGuideMeasurement none = measure_skull_guides(head.skull, no_nasion);
  EXPECT_FALSE(none.guides.nasal_aperture_left_mm.has_value());
}

TEST(SkullGuides, SpineLengthIsHowFarAnsStandsInFrontOfPointA) {
  const TemplateHead& head = test::coarse_template_head();
  LandmarkSet landmarks = template_skull_landmarks(head);
  const Vec3 ss = landmarks.at("ss").position_mm;
  landmarks.add({"ans", ss + Vec3(0.0, -7.5, 4.0)});  // anterior is -y
  const SkullGuideMeasurement m = measure_skull_guides(head.skull, landmarks);
  ASSERT_TRUE(m.guides.nasal_spine_tip && m.guides.nasal_spine_base);
  EXPECT_NEAR(m.spine_length_mm, 7.5, 1e-9);
  EXPECT_NEAR((*m.guides.nasal_spine_base - (ss + Vec3(0.0, 0.0, 4.0))).norm(), 0.0, 1e-9);
  EXPECT_TRUE(m.missing.empty());

  // Given guide values win over the measured ones; the rest stay measured.
  FaceGuides given;
  given.mouth_corner_left_mm = 30.0;
  given.lip_parting_mm = -40.0;
  const FaceGuides merged = merge_face_guides(m.guides, given);
  EXPECT_EQ(*merged.mouth_corner_left_mm, 30.0);
  EXPECT_EQ(*merged.lip_parting_mm, -40.0);
  EXPECT_EQ(*merged.mouth_corner_right_mm, *m.guides.mouth_corner_right_mm);
  EXPECT_EQ(*merged.nasal_aperture_left_mm, *m.guides.nasal_aperture_left_mm);
  EXPECT_EQ(*merged.nasal_spine_tip, *m.guides.nasal_spine_tip);
  EXPECT_FALSE(any_guide(FaceGuides{}));
  EXPECT_TRUE(any_guide(merged));
}

TEST(SkullGuides, MissingLandmarksAreReportedAndAnEmptySkullIsRefused) {
  const TemplateHead& head = test::coarse_template_head();
  const SkullGuideMeasurement none = measure_skull_guides(head.skull, LandmarkSet("empty"));
  EXPECT_TRUE(none.measured.empty());
  EXPECT_EQ(none.missing.size(), 3u);
  EXPECT_FALSE(any_guide(none.guides));
  EXPECT_THROW(measure_skull_guides(TriMesh{}, LandmarkSet("x")), InputError);
  SkullGuideOptions bad;
  bad.sample_step_mm = 0.0;
  EXPECT_THROW(measure_skull_guides(head.skull, LandmarkSet("x"), nullptr, bad), InputError);
}

}  // namespace
}  // namespace forensim
