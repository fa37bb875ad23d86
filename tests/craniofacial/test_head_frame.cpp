#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/head_frame.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

// Landmarks of a symmetric skull in its own head frame (LPS: x left, y posterior, z superior), origin at the
// porions' midpoint; the Frankfort plane is z = 0.
const std::map<std::string, Vec3> k_canonical = {
    {"po_L", Vec3(68, 0, 0)},     {"po_R", Vec3(-68, 0, 0)},    {"or_L", Vec3(33, -78, 0)},
    {"or_R", Vec3(-33, -78, 0)},  {"n", Vec3(0, -92, 18)},      {"g", Vec3(0, -95, 32)},
    {"pr", Vec3(0, -88, -42)},    {"pg", Vec3(0, -82, -80)},    {"zy_L", Vec3(66, -38, -8)},
    {"zy_R", Vec3(-66, -38, -8)}, {"go_L", Vec3(48, -18, -70)}, {"go_R", Vec3(-48, -18, -70)},
    {"v", Vec3(0, -5, 110)},      {"op", Vec3(0, 95, 30)}};

Eigen::Affine3d pose() {
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  t.rotate(Eigen::AngleAxisd(0.7, Vec3(0.3, -1.0, 0.4).normalized()));
  t.pretranslate(Vec3(120.5, -43.0, 811.0));
  return t;
}

LandmarkSet posed_landmarks(const Eigen::Affine3d& t, bool pairs = true) {
  LandmarkSet set("synthetic");
  for (const auto& [name, p] : k_canonical) {
    const bool bilateral = name.find("_") != std::string::npos;
    if (!pairs && bilateral && name.rfind("po_", 0) != 0 && name.rfind("or_", 0) != 0) continue;
    set.add({name, t * p, LandmarkSource::imported, 1.0});
  }
  return set;
}

}  // namespace

TEST(HeadFrame, RecoversTheFrameOfAPosedSkull) {
  const Eigen::Affine3d t = pose();
  const LandmarkSet world = posed_landmarks(t);
  const HeadFrame frame = head_frame_from_landmarks(world);
  EXPECT_LT((frame.axes.transpose() * frame.axes - Mat3::Identity()).norm(), 1e-12);
  EXPECT_NEAR(frame.axes.determinant(), 1.0, 1e-12);
  EXPECT_LT((frame.axes - t.linear()).norm(), 1e-12);
  EXPECT_LT((frame.origin - t.translation()).norm(), 1e-9);
  EXPECT_LT(frame.perpendicularity_deg, 1e-9);
  for (const auto& [name, p] : k_canonical) {
    EXPECT_LT((frame.to_head(world.at(name).position_mm) - p).norm(), 1e-9) << name;
    EXPECT_LT((frame.world_to_head() * world.at(name).position_mm - p).norm(), 1e-9) << name;
    EXPECT_LT((frame.to_world(p) - world.at(name).position_mm).norm(), 1e-9) << name;
  }
  // The Frankfort normal points superior, the midsagittal normal towards the left.
  EXPECT_LT((frame.frankfort.normal - t.linear() * Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_LT((frame.midsagittal.normal - t.linear() * Vec3::UnitX()).norm(), 1e-12);
}

TEST(HeadFrame, MidsagittalPlaneFromMidlineLandmarksAlone) {
  const Eigen::Affine3d t = pose();
  LandmarkSet midline("midline");
  for (const std::string name : {"n", "g", "pr", "pg", "v", "op"}) {
    midline.add({name, t * k_canonical.at(name), LandmarkSource::imported, 1.0});
  }
  const Plane plane = midsagittal_plane(midline);
  EXPECT_LT(std::abs(std::abs(plane.normal.dot(t.linear() * Vec3::UnitX())) - 1.0), 1e-12);
  EXPECT_GT(plane.normal.x(), 0.0);
  for (const Landmark& l : midline.landmarks()) EXPECT_NEAR(plane.signed_distance(l.position_mm), 0.0, 1e-9);
}

TEST(HeadFrame, AsymmetricPairsStillGiveAPerpendicularFrame) {
  // Move one zygion: the midsagittal estimate tilts, the frame stays orthonormal and keeps the exact
  // Frankfort plane.
  LandmarkSet set = posed_landmarks(Eigen::Affine3d::Identity());
  set.set({"zy_L", Vec3(70, -30, -2), LandmarkSource::edited, 1.0});
  const HeadFrame frame = head_frame_from_landmarks(set);
  EXPECT_LT((frame.axes.col(2) - Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_LT((frame.axes.transpose() * frame.axes - Mat3::Identity()).norm(), 1e-12);
  EXPECT_GT(frame.perpendicularity_deg, 0.0);
  EXPECT_NEAR(frame.to_head(set.at("po_L").position_mm).z(), 0.0, 1e-9);
}

TEST(HeadFrame, MissingLandmarksAreNamed) {
  LandmarkSet set = posed_landmarks(Eigen::Affine3d::Identity());
  set.remove("po_R");
  try {
    frankfort_plane(set);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("po_R"), std::string::npos) << e.what();
  }
  LandmarkSet no_or = posed_landmarks(Eigen::Affine3d::Identity());
  no_or.remove("or_L");
  EXPECT_NO_THROW(frankfort_plane(no_or));  // or_R stands in
  no_or.remove("or_R");
  EXPECT_THROW(frankfort_plane(no_or), InputError);
  LandmarkSet two("two");
  two.add({"n", Vec3(0, -90, 0), LandmarkSource::imported, 1.0});
  two.add({"g", Vec3(0, -92, 15), LandmarkSource::imported, 1.0});
  EXPECT_THROW(midsagittal_plane(two), InputError);
}

TEST(HeadFrame, SymmetryPlaneOfAMirrorSymmetricMeshFromAPerturbedStart) {
  // An icosphere bent by a map that is even in x: mirror-symmetric about x = 0, asymmetric front to back and
  // top to bottom, then posed.
  TriMesh mesh = make_icosphere(Vec3::Zero(), 70.0, 4);
  for (Vec3& p : mesh.positions) {
    const double x = p.x(), y = p.y(), z = p.z();
    p = Vec3(x * (1.0 + 0.002 * y), 1.2 * y + 0.004 * x * x + 0.003 * z * z, z + 0.003 * y * y);
  }
  const Eigen::Affine3d t = pose();
  for (Vec3& p : mesh.positions) p = t * p;
  const Plane truth{t * Vec3::Zero(), t.linear() * Vec3::UnitX()};
  Plane start = truth;
  start.normal = Eigen::AngleAxisd(8.0 * M_PI / 180.0, t.linear() * Vec3(0, 1, 1).normalized()) * truth.normal;
  start.point = truth.point + 6.0 * truth.normal;
  const SymmetryPlaneFit fit = fit_symmetry_plane(mesh, start);
  const double angle = std::acos(std::clamp(fit.plane.normal.dot(truth.normal), -1.0, 1.0)) * 180.0 / M_PI;
  EXPECT_LT(angle, 0.1);
  EXPECT_LT(std::abs(truth.signed_distance(fit.plane.point)), 0.1);
  EXPECT_LT(fit.rms_mm, 0.5);
  EXPECT_GT(fit.iterations, 1);
  // The start was far from symmetric: its mirrored vertices miss the mesh by millimetres.
  SymmetryPlaneOptions none;
  none.max_iterations = 0;
  EXPECT_GT(fit_symmetry_plane(mesh, start, none).rms_mm, 10.0 * fit.rms_mm);
}

TEST(HeadFrame, FrameFromTheSkullsSymmetryPlaneCorrectsRoughLandmarks) {
  TriMesh mesh = make_icosphere(Vec3::Zero(), 70.0, 4);
  for (Vec3& p : mesh.positions) {
    const double x = p.x(), y = p.y(), z = p.z();
    p = Vec3(x * (1.0 + 0.002 * y), 1.2 * y + 0.004 * x * x + 0.003 * z * z, z + 0.003 * y * y);
  }
  const Eigen::Affine3d t = pose();
  for (Vec3& p : mesh.positions) p = t * p;
  LandmarkSet rough = posed_landmarks(t);
  // A zygion placed 5 mm off tilts the landmark midsagittal plane; the skull's symmetry plane does not tilt.
  rough.set({"zy_L", t * (k_canonical.at("zy_L") + Vec3(0, 5, 3)), LandmarkSource::edited, 1.0});
  const HeadFrame from_landmarks = head_frame_from_landmarks(rough);
  SymmetryPlaneFit fit;
  const HeadFrame from_skull = head_frame_from_skull(mesh, rough, {}, &fit);
  const Vec3 true_x = t.linear() * Vec3::UnitX();
  const auto angle = [](const Vec3& a, const Vec3& b) {
    return std::acos(std::clamp(a.dot(b), -1.0, 1.0)) * 180.0 / M_PI;
  };
  EXPECT_GT(angle(from_landmarks.midsagittal.normal, true_x), 0.2);
  EXPECT_LT(angle(from_skull.midsagittal.normal, true_x), 0.1);
  EXPECT_LT(angle(from_skull.axes.col(2), t.linear() * Vec3::UnitZ()), 1e-9);  // Frankfort plane is exact
  EXPECT_LT(fit.rms_mm, 0.5);
}

TEST(HeadFrame, SymmetryPlaneIsTheSameAtAnyThreadCount) {
  TriMesh mesh = make_icosphere(Vec3(3, 1, -2), 60.0, 3);
  for (Vec3& p : mesh.positions) p = Vec3(p.x(), p.y() + 0.004 * p.x() * p.x(), p.z() + 0.002 * p.y() * p.y());
  const Plane start{Vec3(5, 1, -2), Vec3(1, 0.1, 0.05).normalized()};
  const int threads = thread_count();
  set_thread_count(1);
  const SymmetryPlaneFit one = fit_symmetry_plane(mesh, start);
  set_thread_count(4);
  const SymmetryPlaneFit four = fit_symmetry_plane(mesh, start);
  set_thread_count(threads);
  EXPECT_EQ(one.plane.normal, four.plane.normal);
  EXPECT_EQ(one.plane.point, four.plane.point);
  EXPECT_EQ(one.iterations, four.iterations);
}
