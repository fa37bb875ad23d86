#include "craniofacial/landmark_detection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/primitives.hpp"
#include "synthetic_skull.hpp"

using namespace forensim;
using namespace forensim::test;

namespace {

TriMesh ellipsoid(const Vec3& axes, int subdivisions = 6) {
  TriMesh mesh = make_icosphere(Vec3::Zero(), 1.0, subdivisions);
  for (Vec3& p : mesh.positions) p = axes.cwiseProduct(p);
  mesh.normals.clear();
  return mesh;
}

}  // namespace

TEST(LandmarkDetection, ExtremalRefinementFindsTheAnalyticExtremum) {
  const TriMesh mesh = ellipsoid(Vec3(70, 90, 80));
  const HeadFrame frame = identity_frame();
  // Vertex: highest midline point (0, 0, 80), from a start 9 mm off.
  const RefinedLandmark v = refine_landmark(mesh, frame, *landmark_definition("v"), Side::none, Vec3(3, 8, 79));
  EXPECT_LT((v.position_mm - Vec3(0, 0, 80)).norm(), 1.0);
  EXPECT_FALSE(v.at_search_limit);
  // Zygion: most lateral point, left at +x, right at -x.
  const RefinedLandmark zl = refine_landmark(mesh, frame, *landmark_definition("zy_L"), Side::left, Vec3(69, 5, -6));
  const RefinedLandmark zr = refine_landmark(mesh, frame, *landmark_definition("zy_R"), Side::right, Vec3(-69, 5, -6));
  EXPECT_LT((zl.position_mm - Vec3(70, 0, 0)).norm(), 1.0);
  EXPECT_LT((zr.position_mm - Vec3(-70, 0, 0)).norm(), 1.0);
  // Pogonion: most anterior (-y) midline point.
  const RefinedLandmark pg = refine_landmark(mesh, frame, *landmark_definition("pg"), Side::none, Vec3(1, -89, 5));
  EXPECT_LT((pg.position_mm - Vec3(0, -90, 0)).norm(), 1.0);
  EXPECT_LT(std::abs(pg.position_mm.x()), 1e-9);  // on the midsagittal profile
}

TEST(LandmarkDetection, SharperExtremaScoreHigher) {
  const HeadFrame frame = identity_frame();
  const LandmarkDefinition v = *landmark_definition("v");
  const RefinedLandmark flat = refine_landmark(ellipsoid(Vec3(90, 90, 90)), frame, v, Side::none, Vec3(0, 2, 90));
  const RefinedLandmark sharp = refine_landmark(ellipsoid(Vec3(25, 25, 90)), frame, v, Side::none, Vec3(0, 2, 90));
  EXPECT_GT(sharp.sharpness, flat.sharpness);
  EXPECT_GT(flat.sharpness, 0.0);
  EXPECT_LE(sharp.sharpness, 1.0);
  // Started on the side of the vault, "highest" within the radius is no local extremum: it lies at the limit.
  const RefinedLandmark side = refine_landmark(ellipsoid(Vec3(90, 90, 90)), frame, v, Side::none,
                                               Vec3(0, 90 * std::sin(0.8), 90 * std::cos(0.8)));
  EXPECT_TRUE(side.at_search_limit);
  EXPECT_LT(side.sharpness, flat.sharpness);
}

TEST(LandmarkDetection, MidlineRuleSnapsToTheMidsagittalPlane) {
  const TriMesh mesh = ellipsoid(Vec3(70, 90, 80));
  const RefinedLandmark sg =
      refine_landmark(mesh, identity_frame(), *landmark_definition("sg"), Side::none, Vec3(4, -80, 35));
  EXPECT_LT(std::abs(sg.position_mm.x()), 1e-9);
  EXPECT_LT((sg.position_mm - Vec3(4, -80, 35)).norm(), 6.0);
}

TEST(LandmarkDetection, TransferredAndRefinedLandmarksLandOnTheKnownPositions) {
  const TriMesh reference = skull_mesh(6);
  const LandmarkSet reference_landmarks = refine_landmarks(reference, identity_frame(), rough_skull_landmarks());
  const Similarity truth = known_similarity();
  const TriMesh target = moved(reference, truth, true);
  const LandmarkDetection detection = detect_landmarks(reference, reference_landmarks, target);
  ASSERT_EQ(detection.landmarks.size(), reference_landmarks.size());
  for (std::size_t i = 0; i < reference_landmarks.size(); ++i) {
    const Landmark& l = detection.landmarks[i];
    const Vec3 known = truth.apply(deform(reference_landmarks[i].position_mm));
    const double error = (l.position_mm - known).norm();
    const DetectedLandmark& d = detection.details[i];
    std::printf("%-5s %-8s error %.2f mm (transferred %.2f) residual %.3f sharpness %.2f symmetry %.2f conf %.2f\n",
                l.name.c_str(), to_string(d.rule).c_str(), error, (d.transferred_mm - known).norm(), d.residual_mm,
                d.sharpness, d.symmetry_error_mm, d.confidence);
    EXPECT_LT(error, 2.0) << l.name;
    EXPECT_EQ(l.source, LandmarkSource::detected);
    EXPECT_GT(l.confidence, 0.0) << l.name;
    EXPECT_LE(l.confidence, 1.0) << l.name;
  }
  // The target's head frame is the similarity's image of the reference's own frame.
  EXPECT_LT((detection.frame.midsagittal.normal - truth.rotation * Vec3::UnitX()).norm(), 0.05);
}

TEST(LandmarkDetection, SameLandmarksAtAnyThreadCount) {
  const TriMesh reference = skull_mesh(4);
  const LandmarkSet reference_landmarks = refine_landmarks(reference, identity_frame(), rough_skull_landmarks());
  const TriMesh target = moved(reference, known_similarity(), true);
  set_thread_count(1);
  const LandmarkDetection one = detect_landmarks(reference, reference_landmarks, target);
  set_thread_count(3);
  const LandmarkDetection three = detect_landmarks(reference, reference_landmarks, target);
  set_thread_count(0);
  ASSERT_EQ(one.landmarks.size(), three.landmarks.size());
  for (std::size_t i = 0; i < one.landmarks.size(); ++i) {
    EXPECT_EQ(one.landmarks[i].position_mm, three.landmarks[i].position_mm);
    EXPECT_EQ(one.landmarks[i].confidence, three.landmarks[i].confidence);
  }
}

TEST(LandmarkDetection, BadInputIsRejected) {
  const TriMesh mesh = skull_mesh(3);
  const LandmarkSet rough = rough_skull_landmarks();
  EXPECT_THROW(detect_landmarks(mesh, LandmarkSet("empty"), mesh), InputError);
  LandmarkSet no_porion = rough;
  no_porion.remove("po_L");
  EXPECT_THROW(detect_landmarks(mesh, no_porion, mesh), InputError);
  EXPECT_THROW(detect_landmarks(mesh, rough, TriMesh{}), InputError);
  EXPECT_THROW(refine_landmark(TriMesh{}, identity_frame(), *landmark_definition("v"), Side::none, Vec3::Zero()),
               InputError);
  LandmarkDefinition no_radius = *landmark_definition("v");
  no_radius.search_radius_mm = 0.0;
  EXPECT_THROW(refine_landmark(mesh, identity_frame(), no_radius, Side::none, Vec3::Zero()), InputError);
  EXPECT_FALSE(landmark_definition("not a landmark").has_value());
  EXPECT_EQ(landmark_definition("left zygion")->site, "zy");
}

TEST(LandmarkDetection, ReferenceFrameReplacesTheFrankfortLandmarks) {
  const TriMesh reference = skull_mesh(5);
  LandmarkSet reference_landmarks = refine_landmarks(reference, identity_frame(), rough_skull_landmarks());
  for (const char* name : {"po_L", "po_R", "or_L", "or_R"}) reference_landmarks.remove(name);
  const Similarity truth = known_similarity();
  const TriMesh target = moved(reference, truth, true);
  const LandmarkDetection detection = detect_landmarks(reference, reference_landmarks, identity_frame(), target);
  EXPECT_LT((detection.frame.axes - truth.rotation).norm(), 0.05);
  EXPECT_LT((detection.frame.axes.transpose() * detection.frame.axes - Mat3::Identity()).norm(), 1e-12);
  for (std::size_t i = 0; i < reference_landmarks.size(); ++i) {
    const Vec3 known = truth.apply(deform(reference_landmarks[i].position_mm));
    EXPECT_LT((detection.landmarks[i].position_mm - known).norm(), 2.0) << reference_landmarks[i].name;
  }
}
