#include "pbd/velocity_damping.hpp"

#include <Eigen/LU>
#include <algorithm>

#include "core/parallel.hpp"

namespace forensim {
namespace {

constexpr std::size_t block = 2048;

/// Sum over fixed blocks of f(i, partial), partial blocks added in block order.
template <class Acc, class F>
Acc block_sum(std::size_t n, const F& f) {
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<Acc> partial(blocks);
  parallel_for(
      0, blocks,
      [&](std::size_t b) {
        Acc acc;
        for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i) f(i, acc);
        partial[b] = acc;
      },
      1);
  Acc total;
  for (const Acc& a : partial) total += a;
  return total;
}

struct Moments {
  double mass = 0.0;
  Vec3 mx = Vec3::Zero(), mv = Vec3::Zero();
  Moments& operator+=(const Moments& o) {
    mass += o.mass;
    mx += o.mx;
    mv += o.mv;
    return *this;
  }
};

struct Angular {
  Vec3 l = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  Angular& operator+=(const Angular& o) {
    l += o.l;
    inertia += o.inertia;
    return *this;
  }
};

}  // namespace

void damp_velocities(const std::vector<Vec3>& positions, const std::vector<double>& inverse_masses,
                     std::vector<Vec3>& velocities, double k_damping) {
  const std::size_t n = positions.size();
  if (n == 0 || k_damping <= 0.0) return;
  const Moments m = block_sum<Moments>(n, [&](std::size_t i, Moments& acc) {
    if (inverse_masses[i] <= 0.0) return;
    const double mi = 1.0 / inverse_masses[i];
    acc.mass += mi;
    acc.mx += mi * positions[i];
    acc.mv += mi * velocities[i];
  });
  if (m.mass <= 0.0) return;
  const Vec3 x_cm = m.mx / m.mass, v_cm = m.mv / m.mass;
  const Angular a = block_sum<Angular>(n, [&](std::size_t i, Angular& acc) {
    if (inverse_masses[i] <= 0.0) return;
    const double mi = 1.0 / inverse_masses[i];
    const Vec3 r = positions[i] - x_cm;
    acc.l += r.cross(mi * velocities[i]);
    // [r]x [r]x^T = |r|^2 I - r r^T
    acc.inertia += mi * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
  });
  // A collinear particle set has a singular inertia: then only the translation is kept.
  const Eigen::FullPivLU<Mat3> lu(a.inertia);
  const Vec3 omega = lu.isInvertible() ? Vec3(lu.solve(a.l)) : Vec3::Zero();
  const double k = std::min(1.0, k_damping);
  parallel_for(0, n, [&](std::size_t i) {
    if (inverse_masses[i] <= 0.0) return;
    const Vec3 rigid = v_cm + omega.cross(positions[i] - x_cm);
    velocities[i] += k * (rigid - velocities[i]);
  });
}

void damp_relative_velocities(std::vector<Vec3>& velocities, const std::vector<Vec3>& frame_velocities,
                              double k_damping) {
  const double keep = 1.0 - std::clamp(k_damping, 0.0, 1.0);
  parallel_for(0, velocities.size(), [&](std::size_t i) {
    velocities[i] = frame_velocities[i] + keep * (velocities[i] - frame_velocities[i]);
  });
}

}  // namespace forensim
