#include "pbd/stretch_constraint.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/error.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

Vec3 random_point(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {u(rng), u(rng), u(rng)};
}

}  // namespace

TEST(StretchConstraint, ProjectionScalesTheViolationByOneMinusStiffness) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 p0 = random_point(rng), p1 = random_point(rng);
    const double rest = 0.5 + 0.01 * trial;
    for (double k : {1.0, 0.5, 0.2}) {
      const PairCorrection d = project_stretch(p0, p1, 1.0, 2.5, rest, k);
      const double before = stretch_value(p0, p1, rest);
      const double after = stretch_value(p0 + d.dp0, p1 + d.dp1, rest);
      EXPECT_NEAR(after, (1.0 - k) * before, 1e-12);
      if (std::abs(before) > 1e-9) {
        EXPECT_LT(std::abs(after), std::abs(before) + 1e-15);
      }
    }
  }
}

TEST(StretchConstraint, ConservesLinearMomentum) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 p0 = random_point(rng), p1 = random_point(rng);
    // Equal masses: the corrections cancel.
    const PairCorrection equal = project_stretch(p0, p1, 1.0, 1.0, 0.3, 0.7);
    EXPECT_LT((equal.dp0 + equal.dp1).norm(), 1e-14);
    // Unequal masses m = 1 / w: sum m dp = 0, and a fixed particle (w = 0) does not move.
    const PairCorrection unequal = project_stretch(p0, p1, 0.5, 2.0, 0.3, 0.7);
    EXPECT_LT((unequal.dp0 / 0.5 + unequal.dp1 / 2.0).norm(), 1e-13);
    const PairCorrection fixed = project_stretch(p0, p1, 0.0, 1.0, 0.3, 1.0);
    EXPECT_EQ(fixed.dp0, Vec3::Zero());
  }
}

TEST(StretchConstraint, DegenerateCasesMoveNothing) {
  const Vec3 p(1, 2, 3);
  const PairCorrection same = project_stretch(p, p, 1.0, 1.0, 1.0, 1.0);
  EXPECT_EQ(same.dp0, Vec3::Zero());
  const PairCorrection fixed = project_stretch(p, Vec3::Zero(), 0.0, 0.0, 1.0, 1.0);
  EXPECT_EQ(fixed.dp1, Vec3::Zero());
}

TEST(StretchConstraints, OnePerEdgeWithRestLengths) {
  const TriMesh box = make_box_mesh(Vec3::Zero(), Vec3(2, 3, 4), 2);
  const StretchConstraints c = make_stretch_constraints(box.positions, box.triangles, "box");
  // A closed triangle mesh of genus 0 has E = 3 F / 2 edges.
  EXPECT_EQ(c.size(), 3 * box.triangle_count() / 2);
  for (std::size_t e = 0; e < c.size(); ++e) {
    EXPECT_LT(c.edge_vertices[e][0], c.edge_vertices[e][1]);
    EXPECT_DOUBLE_EQ(stretch_value(box.positions[c.edge_vertices[e][0]], box.positions[c.edge_vertices[e][1]],
                                   c.edge_rest_length[e]),
                     0.0);
  }
}

TEST(StretchConstraints, RejectsBadMeshes) {
  const std::vector<Vec3> p{Vec3::Zero(), Vec3::UnitX(), Vec3::Zero()};
  EXPECT_THROW(make_stretch_constraints(p, {Tri{0, 1, 2}}, "mesh"), InputError);  // zero-length edge 0-2
  EXPECT_THROW(make_stretch_constraints(p, {Tri{0, 1, 7}}, "mesh"), InputError);
}
