// Automatic landmarks with the template head as the reference: on the template's own skull they are its
// landmarks; on that skull turned, scaled and moved they land within 2 mm of the moved known positions.
#include "craniofacial/template_landmark_detection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdio>

#include "core/error.hpp"
#include "template_head_fixture.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;

TEST(TemplateLandmarkDetection, OnTheTemplatesOwnSkullGivesItsLandmarks) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet known = template_skull_landmarks(head);
  const LandmarkDetection d = detect_template_landmarks(head, head.skull);
  ASSERT_EQ(d.landmarks.size(), known.size());
  for (const Landmark& l : d.landmarks.landmarks()) {
    EXPECT_LT((l.position_mm - known.at(l.name).position_mm).norm(), 0.05) << l.name;
    EXPECT_EQ(l.source, LandmarkSource::detected);
  }
}

TEST(TemplateLandmarkDetection, MovedSkullLandmarksLandWithin2mmOfTheKnownPositions) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet known = template_skull_landmarks(head);
  const double scale = 1.06;
  const Mat3 rotation = (Eigen::AngleAxisd(0.12, Vec3::UnitZ()) * Eigen::AngleAxisd(-0.08, Vec3::UnitX())).matrix();
  const Vec3 translation(12.0, -7.0, 25.0);
  TriMesh skull = head.skull;
  for (Vec3& p : skull.positions) p = scale * (rotation * p) + translation;
  skull.normals.clear();
  const LandmarkDetection d = detect_template_landmarks(head, skull);
  ASSERT_EQ(d.landmarks.size(), known.size());
  EXPECT_NEAR(d.registration.similarity.scale, scale, 0.01);
  for (std::size_t i = 0; i < d.landmarks.size(); ++i) {
    const Landmark& l = d.landmarks[i];
    const Vec3 expected = scale * (rotation * known.at(l.name).position_mm) + translation;
    const DetectedLandmark& detail = d.details[i];
    std::printf("%-8s %-8s error %.2f mm, transferred %.2f mm, confidence %.2f\n", l.name.c_str(),
                to_string(detail.rule).c_str(), (l.position_mm - expected).norm(),
                (detail.transferred_mm - expected).norm(), l.confidence);
    EXPECT_LT((l.position_mm - expected).norm(), 2.0) << l.name;
    EXPECT_GE(l.confidence, 0.0);
    EXPECT_LE(l.confidence, 1.0);
    EXPECT_EQ(d.details[i].refined_mm, l.position_mm);
  }
}

TEST(TemplateLandmarkDetection, EmptySkullIsRejected) {
  EXPECT_THROW(detect_template_landmarks(coarse_template_head(), TriMesh{}), InputError);
}
