#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/random.hpp"
#include "craniofacial/skull_normals.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

Vec3 random_direction(RandomStream& rng) {
  while (true) {
    const Vec3 v(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (v.norm() > 0.1 && v.norm() < 1.0) return v.normalized();
  }
}

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

TEST(SkullNormals, OnASphereTheDirectionIsRadial) {
  const Vec3 center(10, -20, 30);
  const double radius = 80.0;
  const SkullSurface sphere(make_icosphere(center, radius, 5));
  RandomStream rng(7, 0);
  double worst = 0.0, worst_facet = 0.0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 d = random_direction(rng);
    const Vec3 landmark = center + (radius + rng.uniform(-2.0, 2.0)) * d;
    const ClosestPoint at = sphere.closest_point(landmark);
    const Vec3 radial = at.point - center;
    worst = std::max(worst, angle_deg(sphere.landmark_direction(landmark, 8.0), radial));
    worst_facet = std::max(worst_facet, angle_deg(sphere.patch_normal(at, 0.0), radial));
  }
  // A single facet's normal is off by up to half a facet's angle (~1.1 degrees at 5 subdivisions); the patch
  // average over an 8 mm radius is much closer to radial.
  EXPECT_LT(worst, 0.35);
  EXPECT_GT(worst_facet, worst);
}

TEST(SkullNormals, FlatFaceGivesItsNormalAndThinPlatesDoNotMixSides) {
  // A 1 mm thin plate: its top at z = 1, bottom at z = 0. A 5 mm patch reaches the sides and the bottom around
  // the rim, which must not count (they face away from the landmark's triangle).
  const SkullSurface plate(make_box_mesh(Vec3(0, 0, 0), Vec3(40, 40, 1), 8));
  const Vec3 top = plate.landmark_direction(Vec3(20, 20, 1.2), 5.0);
  EXPECT_LT((top - Vec3::UnitZ()).norm(), 1e-12);
  const Vec3 edge = plate.landmark_direction(Vec3(20, 0.5, 1.0), 5.0);  // near the rim of the top face
  EXPECT_LT((edge - Vec3::UnitZ()).norm(), 1e-12);
  const Vec3 bottom = plate.landmark_direction(Vec3(20, 20, -0.5), 5.0);
  EXPECT_LT((bottom + Vec3::UnitZ()).norm(), 1e-12);
}

TEST(SkullNormals, DepthVectorsHaveTheTablesLengthsAndDirections) {
  const Vec3 center = Vec3::Zero();
  const double radius = 90.0;
  const SkullSurface sphere(make_icosphere(center, radius, 5));
  const TissueDepths depths = select_tissue_depths(built_in_tissue_depth_table("ttable_2023"));
  LandmarkSet skull("test skull");
  skull.add({"n", Vec3(0, -radius - 0.3, 5), LandmarkSource::imported, 1.0});
  skull.add({"g", Vec3(0, -radius * 0.95, 28), LandmarkSource::detected, 0.9});
  skull.add({"zy_L", Vec3(radius, -10, 0), LandmarkSource::edited, 1.0});
  skull.add({"ecm2i_R", Vec3(-70, -50, -30).normalized() * radius, LandmarkSource::detected, 0.6});
  skull.add({"po_L", Vec3(radius, 5, 0), LandmarkSource::imported, 1.0});
  skull.add({"sg", Vec3(0, -0.9, 0.43).normalized() * radius, LandmarkSource::imported, 1.0});
  const DepthVectors result = depth_vectors(sphere, skull, depths);
  ASSERT_EQ(result.vectors.size(), 4u);
  EXPECT_EQ(result.unpaired, std::vector<std::string>{"po_L"});
  EXPECT_EQ(result.missing, std::vector<std::string>{"sg"});  // a Rhine-only site: no T-Table value
  const std::vector<std::pair<std::string, double>> expected = {
      {"se'", 6.0}, {"g'", 5.5}, {"zy'_L", 7.5}, {"iM2'_R", 22.0}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const DepthVector& v = result.vectors[i];
    EXPECT_EQ(v.skin_landmark, expected[i].first);
    EXPECT_EQ(v.depth_mm, expected[i].second);
    EXPECT_NEAR((v.skin_mm - v.bone_mm).norm(), expected[i].second, 1e-12);
    EXPECT_NEAR(v.direction.norm(), 1.0, 1e-12);
    EXPECT_LT(angle_deg(v.direction, v.bone_mm - center), 0.5);
    EXPECT_NEAR(v.bone_mm.norm(), radius, 0.1);  // on the (faceted) sphere
    EXPECT_NE(v.depth_source.find("Hona and Stephan 2024"), std::string::npos);
  }
  EXPECT_NEAR(result.vectors[0].surface_offset_mm, skull.at("n").position_mm.norm() - radius, 0.05);
  EXPECT_EQ(result.vectors[1].source, LandmarkSource::detected);
  EXPECT_EQ(result.vectors[1].confidence, 0.9);
  const LandmarkSet skin = skin_landmarks(result);
  EXPECT_EQ(skin.names(), (std::vector<std::string>{"se'", "g'", "zy'_L", "iM2'_R"}));
  EXPECT_EQ(skin.at("zy'_L").position_mm, result.vectors[2].skin_mm);
}

TEST(SkullNormals, LandmarksFarFromTheSkullOrUnknownAreErrors) {
  const SkullSurface sphere(make_icosphere(Vec3::Zero(), 90.0, 3));
  const TissueDepths depths = select_tissue_depths(built_in_tissue_depth_table("ttable_2023"));
  LandmarkSet far("far");
  far.add({"n", Vec3(0, -120, 0), LandmarkSource::imported, 1.0});
  try {
    depth_vectors(sphere, far, depths);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("30.0 mm from the skull"), std::string::npos) << e.what();
  }
  LandmarkSet unknown("typo");
  unknown.add({"nasoin", Vec3(0, -90, 0), LandmarkSource::imported, 1.0});
  EXPECT_THROW(depth_vectors(sphere, unknown, depths), InputError);
  EXPECT_THROW(SkullSurface(TriMesh{}), InputError);
}
