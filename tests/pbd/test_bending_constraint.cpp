#include "pbd/bending_constraint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/error.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

Quad random_quad(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Quad q;
  for (Vec3& p : q) p = Vec3(u(rng), u(rng), u(rng));
  return q;
}

/// A hinge: edge along z from 0 to 1, wing 0 at +x, wing 1 turned by `angle` about z from -x (positive: convex
/// seen from +y, the side the normals face).
Quad hinge(double angle) {
  return {Vec3(1, 0, 0.5), Vec3(-std::cos(angle), -std::sin(angle), 0.5), Vec3(0, 0, 0), Vec3(0, 0, 1)};
}

}  // namespace

TEST(BendingConstraint, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(11);
  const double h = 1e-6;
  for (int trial = 0; trial < 40; ++trial) {
    const Quad x = random_quad(rng);
    const DihedralGradient g = dihedral_angle_gradient(x);
    if (std::abs(std::abs(g.angle) - std::numbers::pi) < 1e-3) continue;  // atan2 branch cut
    for (int i = 0; i < 4; ++i) {
      for (int a = 0; a < 3; ++a) {
        Quad plus = x, minus = x;
        plus[i][a] += h;
        minus[i][a] -= h;
        const double fd = (dihedral_angle(plus) - dihedral_angle(minus)) / (2 * h);
        EXPECT_NEAR(g.gradient[i][a], fd, 1e-5 * (1.0 + std::abs(fd))) << "trial " << trial << " x" << i;
      }
    }
    const Vec3 sum = g.gradient[0] + g.gradient[1] + g.gradient[2] + g.gradient[3];
    EXPECT_LT(sum.norm(), 1e-9 * (1.0 + g.gradient[0].norm()));
  }
}

TEST(BendingConstraint, SignedAngleOfAHinge) {
  // Flat pair: 0. Folding one way or the other gives angles of opposite signs and equal size.
  EXPECT_NEAR(dihedral_angle(hinge(0.0)), 0.0, 1e-12);
  const double up = dihedral_angle(hinge(0.4)), down = dihedral_angle(hinge(-0.4));
  EXPECT_NEAR(std::abs(up), 0.4, 1e-12);
  EXPECT_NEAR(up, -down, 1e-12);
}

TEST(BendingConstraint, AngleIsInvariantUnderRigidMotions) {
  std::mt19937 rng(5);
  const Quad x = random_quad(rng);
  const Mat3 r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Quad y;
  for (int i = 0; i < 4; ++i) y[i] = r * x[i] + Vec3(3, -1, 2);
  EXPECT_NEAR(dihedral_angle(x), dihedral_angle(y), 1e-12);
}

TEST(BendingConstraint, ProjectionReducesTheValueAndConservesMomentum) {
  std::mt19937 rng(7);
  int reduced = 0, tried = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Quad x = random_quad(rng);
    const double rest = dihedral_angle(x) + 0.2 * (trial % 2 ? 1.0 : -1.0);
    const double before = bending_value(x, rest);
    const auto d = project_bending(x, Vec4::Ones(), rest, 0.5);
    Vec3 momentum = Vec3::Zero();
    Quad y = x;
    for (int i = 0; i < 4; ++i) {
      y[i] += d[i];
      momentum += d[i];
    }
    EXPECT_LT(momentum.norm(), 1e-12);
    ++tried;
    if (std::abs(bending_value(y, rest)) < std::abs(before)) ++reduced;
  }
  // One linearised projection step may overshoot only on near-degenerate random quads.
  EXPECT_GE(reduced, tried - 2);
  // Full stiffness on a hinge closes most of the gap in one projection and all of it in a few.
  Quad q = hinge(0.6);
  const double target = dihedral_angle(hinge(0.1));
  for (int it = 0; it < 10; ++it) {
    const auto d = project_bending(q, Vec4::Ones(), target, 1.0);
    for (int i = 0; i < 4; ++i) q[i] += d[i];
  }
  EXPECT_NEAR(bending_value(q, target), 0.0, 1e-8);
}

TEST(BendingConstraints, OnePerInteriorEdgeOfAClosedMesh) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 1.0, 2);
  const BendingConstraints c = make_bending_constraints(sphere.positions, sphere.triangles, "sphere");
  EXPECT_EQ(c.size(), 3 * sphere.triangle_count() / 2);
  // A convex surface bends the same way at every edge.
  for (std::size_t b = 0; b < c.size(); ++b) {
    EXPECT_GT(c.rest_angle[b], 0.0) << "pair " << b;
    EXPECT_LT(c.rest_angle[b], 0.5);
  }
  // An open strip of two triangles has one interior edge.
  const std::vector<Vec3> p{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  const BendingConstraints strip = make_bending_constraints(p, {Tri{0, 1, 2}, Tri{0, 2, 3}}, "strip");
  ASSERT_EQ(strip.size(), 1u);
  EXPECT_NEAR(strip.rest_angle[0], 0.0, 1e-12);
  EXPECT_THROW(make_bending_constraints(p, {Tri{0, 1, 9}}, "strip"), InputError);
}
