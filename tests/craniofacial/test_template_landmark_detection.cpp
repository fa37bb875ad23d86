// Automatic landmarks with the template head as the reference: on the template's own skull they are its
// landmarks; on that skull turned, scaled and moved they land within 2 mm of the moved known positions.
#include "craniofacial/template_landmark_detection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

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

namespace {

/// `mesh` without the triangles whose centroid `drop` selects, over the vertices still used.
template <typename Drop>
TriMesh without_triangles(const TriMesh& mesh, Drop&& drop) {
  TriMesh out;
  std::vector<Index> remap(mesh.positions.size(), -1);
  for (const Tri& t : mesh.triangles) {
    const Vec3 centroid =
        (mesh.positions[static_cast<std::size_t>(t[0])] + mesh.positions[static_cast<std::size_t>(t[1])] +
         mesh.positions[static_cast<std::size_t>(t[2])]) /
        3.0;
    if (drop(centroid)) continue;
    Tri kept;
    for (int k = 0; k < 3; ++k) {
      Index& r = remap[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
      if (r < 0) {
        r = static_cast<Index>(out.positions.size());
        out.positions.push_back(mesh.positions[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])]);
      }
      kept[static_cast<std::size_t>(k)] = r;
    }
    out.triangles.push_back(kept);
  }
  return out;
}

}  // namespace

TEST(TemplateLandmarkDetection, ASkullWithoutItsNasalBonesLeavesOutMidNasalAndRhinion) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet known = template_skull_landmarks(head);
  const Vec3 n = known.at("n").position_mm;
  const Vec3 rhi = known.at("rhi").position_mm;
  // On the template's own skull the nasal bones join nasion and rhinion.
  EXPECT_LT(nasal_bone_gap_mm(head.skull, n, rhi), 3.0);
  // The nasal bones cut away, as a CT too coarse for them shows the skull: from just below nasion to rhinion.
  const TriMesh cut = without_triangles(head.skull, [&](const Vec3& c) {
    return std::abs(c.x()) < 12.0 && c.y() < n.y() + 6.0 && c.z() < n.z() - 3.0 && c.z() > rhi.z() - 8.0;
  });
  ASSERT_LT(cut.triangles.size(), head.skull.triangles.size());
  EXPECT_GT(nasal_bone_gap_mm(cut, n, rhi), 4.0);
  const LandmarkDetection d = detect_template_landmarks(head, cut);
  ASSERT_EQ(d.left_out.size(), 2u);
  EXPECT_EQ(d.left_out[0].first, "mn");
  EXPECT_EQ(d.left_out[1].first, "rhi");
  EXPECT_NE(d.left_out[0].second.find("no nasal bones"), std::string::npos);
  EXPECT_EQ(d.landmarks.size(), known.size() - 2);
  ASSERT_EQ(d.details.size(), d.landmarks.size());
  EXPECT_FALSE(d.landmarks.contains("mn"));
  EXPECT_FALSE(d.landmarks.contains("rhi"));
  EXPECT_TRUE(d.landmarks.contains("n"));
  for (std::size_t i = 0; i < d.landmarks.size(); ++i) EXPECT_EQ(d.details[i].name, d.landmarks[i].name);
}

TEST(TemplateLandmarkDetection, NasalBoneGapRejectsAnEmptyMesh) {
  EXPECT_THROW(nasal_bone_gap_mm(TriMesh{}, Vec3::Zero(), Vec3::UnitZ()), InputError);
}

TEST(TemplateLandmarkDetection, EmptySkullIsRejected) {
  EXPECT_THROW(detect_template_landmarks(coarse_template_head(), TriMesh{}), InputError);
}
