#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "tetrahedralize/tet_quality.hpp"

using namespace forensim;

namespace {

TetMesh regular_tet(bool inverted = false) {
  TetMesh m;
  m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.tets = {{0, 1, 2, 3}};
  // This vertex order has negative orientation; swap two to make it positive unless asked otherwise.
  if (!inverted) std::swap(m.tets[0][2], m.tets[0][3]);
  return m;
}

}  // namespace

TEST(TetQuality, RegularTetHasAnalyticRatioAndAngle) {
  const TetQualityReport r = tet_quality(regular_tet());
  ASSERT_EQ(r.tet_count, 1u);
  EXPECT_EQ(r.inverted_count, 0u);
  EXPECT_EQ(r.flat_count, 0u);
  EXPECT_NEAR(r.radius_edge_ratio[0], std::sqrt(6.0) / 4.0, 1e-12);
  EXPECT_NEAR(r.min_dihedral_deg[0], std::acos(1.0 / 3.0) * 180.0 / 3.14159265358979323846, 1e-9);
  EXPECT_EQ(r.radius_edge_histogram[0], 1u);  // <= 0.7
  EXPECT_EQ(r.dihedral_histogram[14], 1u);    // 70-75 degrees
  EXPECT_NE(r.summary().find("1 tets"), std::string::npos);
}

TEST(TetQuality, InvertedRegularTetIsCountedButHasTheSameShape) {
  const TetQualityReport r = tet_quality(regular_tet(true));
  EXPECT_EQ(r.inverted_count, 1u);
  EXPECT_NEAR(r.radius_edge_ratio[0], std::sqrt(6.0) / 4.0, 1e-12);
  EXPECT_NEAR(r.min_dihedral_deg[0], 70.528779, 1e-5);
}

TEST(TetQuality, CornerTetHasKnownAngles) {
  // Corner of a cube: three right dihedral angles at the origin's edges, and three of
  // acos(1/sqrt(3)) = 54.74 degrees at the slanted face.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
  EXPECT_NEAR(tet_min_dihedral_deg(a, b, c, d), std::acos(1.0 / std::sqrt(3.0)) * 180.0 / 3.14159265358979323846, 1e-9);
  // Circumcentre (0.5, 0.5, 0.5): radius sqrt(3)/2 over shortest edge 1.
  EXPECT_NEAR(tet_radius_edge_ratio(a, b, c, d), std::sqrt(3.0) / 2.0, 1e-12);
}

TEST(TetQuality, FlatTetIsFlat) {
  TetMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  m.tets = {{0, 1, 2, 3}};
  const TetQualityReport r = tet_quality(m);
  EXPECT_EQ(r.flat_count, 1u);
  EXPECT_EQ(r.inverted_count, 0u);
  EXPECT_EQ(r.min_dihedral_deg[0], 0.0);
  EXPECT_TRUE(std::isinf(r.radius_edge_ratio[0]));
  EXPECT_EQ(r.radius_edge_histogram.back(), 1u);
  EXPECT_EQ(r.dihedral_histogram[0], 1u);
}

TEST(TetQuality, BadIndexIsInputError) {
  TetMesh m = regular_tet();
  m.tets[0][1] = 7;
  EXPECT_THROW(tet_quality(m), InputError);
}
