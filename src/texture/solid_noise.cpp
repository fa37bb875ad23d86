#include "texture/solid_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/random.hpp"

namespace forensim {
namespace {

double fade(double t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

double lerp(double t, double a, double b) {
  return a + t * (b - a);
}

/// Dot product of the offset with one of Perlin's 12 edge gradients selected by `hash`.
double grad(int hash, double x, double y, double z) {
  const int h = hash & 15;
  const double u = h < 8 ? x : y;
  const double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}

}  // namespace

GradientNoise3::GradientNoise3(std::uint64_t seed) {
  int table[256];
  std::iota(table, table + 256, 0);
  RandomStream random(seed, 0x736f6c6964ULL);
  for (int i = 255; i > 0; --i) {
    const int j = static_cast<int>(random.uniform_int(0, i));
    std::swap(table[i], table[j]);
  }
  for (int i = 0; i < 512; ++i) m_perm[i] = table[i & 255];
}

double GradientNoise3::evaluate(const Vec3& p) const {
  const double fx = std::floor(p.x()), fy = std::floor(p.y()), fz = std::floor(p.z());
  const int X = static_cast<int>(static_cast<long long>(fx) & 255);
  const int Y = static_cast<int>(static_cast<long long>(fy) & 255);
  const int Z = static_cast<int>(static_cast<long long>(fz) & 255);
  const double x = p.x() - fx, y = p.y() - fy, z = p.z() - fz;
  const double u = fade(x), v = fade(y), w = fade(z);
  const int* P = m_perm;
  const int A = P[X] + Y, AA = P[A] + Z, AB = P[A + 1] + Z;
  const int B = P[X + 1] + Y, BA = P[B] + Z, BB = P[B + 1] + Z;
  return lerp(w,
              lerp(v, lerp(u, grad(P[AA], x, y, z), grad(P[BA], x - 1, y, z)),
                   lerp(u, grad(P[AB], x, y - 1, z), grad(P[BB], x - 1, y - 1, z))),
              lerp(v, lerp(u, grad(P[AA + 1], x, y, z - 1), grad(P[BA + 1], x - 1, y, z - 1)),
                   lerp(u, grad(P[AB + 1], x, y - 1, z - 1), grad(P[BB + 1], x - 1, y - 1, z - 1))));
}

double GradientNoise3::fractal(const Vec3& p, int octaves, double persistence) const {
  double sum = 0.0, amplitude = 1.0, norm = 0.0, frequency = 1.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * evaluate(p * frequency);
    norm += amplitude;
    amplitude *= persistence;
    frequency *= 2.0;
  }
  return norm > 0.0 ? sum / norm : 0.0;
}

WorleyNoise3::WorleyNoise3(std::uint64_t seed, double jitter)
    : m_seed(mix64(seed ^ 0x776f726c6579ULL)), m_jitter(std::clamp(jitter, 0.0, 1.0)) {}

Vec3 WorleyNoise3::feature_point(long long x, long long y, long long z, std::uint64_t& cell) const {
  cell = mix64(m_seed ^ mix64(static_cast<std::uint64_t>(x) * 0x9E3779B1ULL ^
                              mix64(static_cast<std::uint64_t>(y) * 0x85EBCA77ULL ^ static_cast<std::uint64_t>(z))));
  const double jx = hash_uniform(cell, 1), jy = hash_uniform(cell, 2), jz = hash_uniform(cell, 3);
  const double lo = 0.5 - 0.5 * m_jitter;
  return Vec3(static_cast<double>(x) + lo + m_jitter * jx, static_cast<double>(y) + lo + m_jitter * jy,
              static_cast<double>(z) + lo + m_jitter * jz);
}

CellularSample WorleyNoise3::evaluate(const Vec3& p) const {
  const auto cx = static_cast<long long>(std::floor(p.x()));
  const auto cy = static_cast<long long>(std::floor(p.y()));
  const auto cz = static_cast<long long>(std::floor(p.z()));
  double d1 = std::numeric_limits<double>::infinity(), d2 = d1;
  CellularSample out;
  for (long long dz = -1; dz <= 1; ++dz) {
    for (long long dy = -1; dy <= 1; ++dy) {
      for (long long dx = -1; dx <= 1; ++dx) {
        std::uint64_t cell = 0;
        const Vec3 q = feature_point(cx + dx, cy + dy, cz + dz, cell);
        const double d = (q - p).squaredNorm();
        if (d < d1) {
          d2 = d1;
          d1 = d;
          out.cell = cell;
          out.nearest = q;
        } else if (d < d2) {
          d2 = d;
        }
      }
    }
  }
  out.f1 = std::sqrt(d1);
  out.f2 = std::sqrt(d2);
  return out;
}

double WorleyNoise3::cell_value(std::uint64_t cell, std::uint64_t channel) const {
  return hash_uniform(cell, 100 + channel);
}

}  // namespace forensim
