#include "texture/solid_noise.hpp"

#include <cmath>
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

}  // namespace forensim
