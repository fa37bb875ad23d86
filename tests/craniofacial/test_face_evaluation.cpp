// The face evaluation's metric on analytic surfaces: a sphere measured against a concentric sphere gives the
// offset (signed by side), the within-share switches at the tolerance, a region plane through the centre measures
// half the area, an inner (cavity) surface is not measured; the face region's planes from landmarks.
#include "craniofacial/face_evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

// A region far larger than the spheres: everything in it.
FaceRegion everything() {
  FaceRegion r;
  r.coronal = Plane{Vec3(0, 1e6, 0), Vec3::UnitY()};
  r.forehead = Plane{Vec3(0, 0, 1e6), Vec3::UnitZ()};
  r.jaw = Plane{Vec3(0, 0, -1e6), -Vec3::UnitZ()};
  return r;
}

double sphere_area(const TriMesh& m) {
  double a = 0.0;
  for (const Tri& t : m.triangles) {
    a += 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm();
  }
  return a;
}

}  // namespace

TEST(FaceEvaluation, ConcentricSpheresGiveTheOffsetWithItsSign) {
  const TriMesh reconstruction = make_icosphere(Vec3::Zero(), 80.0, 5);
  // Vertices of an icosphere lie on the sphere; the reconstruction's facets lie up to R (1 - cos) inside it, which
  // for level 5 at R = 80 mm is below 0.02 mm.
  for (double offset : {2.0, -1.5, 3.0}) {
    const TriMesh real = make_icosphere(Vec3::Zero(), 80.0 + offset, 3);
    const FaceEvaluation e = evaluate_face(real, reconstruction, everything());
    EXPECT_NEAR(e.signed_mean_mm, offset, 0.03) << offset;
    EXPECT_NEAR(e.mean_abs_mm, std::abs(offset), 0.03) << offset;
    EXPECT_NEAR(e.rms_mm, std::abs(offset), 0.03) << offset;
    EXPECT_NEAR(e.max_abs_mm, std::abs(offset), 0.03) << offset;
    EXPECT_EQ(e.within_share, std::abs(offset) <= 2.5 ? 1.0 : 0.0) << offset;
    EXPECT_EQ(e.vertex_count, real.positions.size());
    EXPECT_NEAR(e.area_mm2, sphere_area(real), 1e-6 * sphere_area(real));
    EXPECT_EQ(e.face.triangle_count(), real.triangle_count());
    ASSERT_TRUE(e.face.vertex_fields.scalars.count("distance"));
  }
}

TEST(FaceEvaluation, ARegionPlaneThroughTheCentreMeasuresTheFrontHalf) {
  const TriMesh reconstruction = make_icosphere(Vec3::Zero(), 80.0, 5);
  const TriMesh real = make_icosphere(Vec3::Zero(), 81.0, 4);
  FaceRegion front = everything();
  front.coronal = Plane{Vec3::Zero(), Vec3::UnitY()};  // in front: y < 0
  const FaceEvaluation e = evaluate_face(real, reconstruction, front);
  // Triangles are kept by their centroid: the half-sphere's area to within one band of triangles.
  const double half = 2.0 * M_PI * 81.0 * 81.0;
  EXPECT_NEAR(e.area_mm2, half, 0.02 * half);
  for (std::size_t i = 0; i < real.positions.size(); ++i) {
    if (real.positions[i].y() > 10.0) {
      EXPECT_TRUE(std::isnan(e.vertex_distance_mm[i])) << i;
    }
    if (real.positions[i].y() < -10.0) {
      EXPECT_NEAR(e.vertex_distance_mm[i], 1.0, 0.03) << i;
    }
  }
  // A region the face does not reach is an error.
  FaceRegion none = everything();
  none.forehead = Plane{Vec3(0, 0, -500.0), Vec3::UnitZ()};
  EXPECT_THROW(evaluate_face(real, reconstruction, none), InputError);
}

TEST(FaceEvaluation, AnInnerCavitySurfaceIsNotMeasured) {
  const TriMesh reconstruction = make_icosphere(Vec3::Zero(), 80.0, 4);
  TriMesh real = make_icosphere(Vec3::Zero(), 81.0, 3);
  // A cavity inside the head: a sphere turned inward (its normals point into the cavity, away from the skin).
  TriMesh cavity = make_icosphere(Vec3(0, -20, 0), 20.0, 2);
  const auto base = static_cast<Index>(real.positions.size());
  for (const Vec3& p : cavity.positions) real.positions.push_back(p);
  for (const Tri& t : cavity.triangles) real.triangles.push_back({t[0] + base, t[2] + base, t[1] + base});
  real.normals.clear();
  const FaceEvaluation e = evaluate_face(real, reconstruction, everything());
  const TriMesh outer = make_icosphere(Vec3::Zero(), 81.0, 3);
  EXPECT_EQ(e.vertex_count, outer.positions.size());
  EXPECT_NEAR(e.mean_abs_mm, 1.0, 0.05);
}

TEST(FaceEvaluation, FaceRegionPlanesFromLandmarks) {
  LandmarkSet skull("skull");
  skull.add({"g", Vec3(0, -90, 30), LandmarkSource::edited, 1.0});
  skull.add({"me", Vec3(0, -80, -90), LandmarkSource::edited, 1.0});
  skull.add({"go_L", Vec3(50, -20, -70), LandmarkSource::edited, 1.0});
  skull.add({"go_R", Vec3(-50, -20, -70), LandmarkSource::edited, 1.0});
  HeadFrame frame;  // LPS axes
  const FaceRegion r = face_region(skull, frame);
  EXPECT_TRUE(r.contains(Vec3(0, -95, 0)));      // the nose's level, in front
  EXPECT_TRUE(r.contains(Vec3(0, -88, 60)));     // the forehead, 30 mm above glabella
  EXPECT_FALSE(r.contains(Vec3(0, -88, 75)));    // above the forehead band
  EXPECT_FALSE(r.contains(Vec3(60, 0, -20)));    // behind the gonia (the ear)
  EXPECT_TRUE(r.contains(Vec3(0, -82, -100)));   // the chin's skin under menton
  EXPECT_FALSE(r.contains(Vec3(0, -40, -120)));  // the neck under the jaw
  skull.remove("go_R");
  EXPECT_THROW(face_region(skull, frame), InputError);
}

TEST(FaceEvaluation, EmptyMeshesAreRejected) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 80.0, 2);
  EXPECT_THROW(evaluate_face(TriMesh{}, sphere, everything()), InputError);
  EXPECT_THROW(evaluate_face(sphere, TriMesh{}, everything()), InputError);
}
