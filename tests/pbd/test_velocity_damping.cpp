#include "pbd/velocity_damping.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/parallel.hpp"

using namespace forensim;

namespace {

struct Cloud {
  std::vector<Vec3> x, v;
  std::vector<double> w;
};

Cloud random_cloud(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.x.emplace_back(u(rng), u(rng), u(rng));
    c.v.emplace_back(u(rng), u(rng), u(rng));
    c.w.push_back(0.5 + 0.5 * (u(rng) + 1.0));
  }
  return c;
}

Vec3 momentum(const Cloud& c) {
  Vec3 p = Vec3::Zero();
  for (std::size_t i = 0; i < c.x.size(); ++i) p += c.v[i] / c.w[i];
  return p;
}

Vec3 angular_momentum(const Cloud& c) {
  Vec3 l = Vec3::Zero();
  for (std::size_t i = 0; i < c.x.size(); ++i) l += c.x[i].cross(c.v[i] / c.w[i]);
  return l;
}

}  // namespace

TEST(VelocityDamping, KeepsRigidMotionAndMomenta) {
  Cloud c = random_cloud(5000, 1);
  // A rigid motion is left as it is.
  Cloud rigid = c;
  const Vec3 v0(0.3, -0.1, 0.2), omega(0.5, 1.0, -0.7);
  for (std::size_t i = 0; i < c.x.size(); ++i) rigid.v[i] = v0 + omega.cross(c.x[i]);
  const std::vector<Vec3> before = rigid.v;
  damp_velocities(rigid.x, rigid.w, rigid.v, 1.0);
  for (std::size_t i = 0; i < c.x.size(); ++i) EXPECT_LT((rigid.v[i] - before[i]).norm(), 1e-10);
  // Any velocity field keeps its linear and angular momentum, and loses kinetic energy.
  const Vec3 p = momentum(c), l = angular_momentum(c);
  double energy = 0.0, energy_after = 0.0;
  for (std::size_t i = 0; i < c.x.size(); ++i) energy += c.v[i].squaredNorm() / c.w[i];
  damp_velocities(c.x, c.w, c.v, 0.3);
  for (std::size_t i = 0; i < c.x.size(); ++i) energy_after += c.v[i].squaredNorm() / c.w[i];
  EXPECT_LT((momentum(c) - p).norm(), 1e-9 * p.norm() + 1e-9);
  EXPECT_LT((angular_momentum(c) - l).norm(), 1e-9 * l.norm() + 1e-9);
  EXPECT_LT(energy_after, energy);
}

TEST(VelocityDamping, RemovesTheGivenFractionOfTheNonRigidPart) {
  Cloud c = random_cloud(2000, 2);
  Cloud full = c;
  damp_velocities(full.x, full.w, full.v, 1.0);  // full.v is the rigid part of c.v
  damp_velocities(c.x, c.w, c.v, 0.25);
  Cloud original = random_cloud(2000, 2);
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    const Vec3 expected = full.v[i] + 0.75 * (original.v[i] - full.v[i]);
    EXPECT_LT((c.v[i] - expected).norm(), 1e-10);
  }
}

TEST(VelocityDamping, SameResultAtAnyThreadCount) {
  Cloud a = random_cloud(20000, 3), b = a;
  set_thread_count(1);
  damp_velocities(a.x, a.w, a.v, 0.5);
  set_thread_count(4);
  damp_velocities(b.x, b.w, b.v, 0.5);
  set_thread_count(0);
  EXPECT_EQ(a.v, b.v);
}
