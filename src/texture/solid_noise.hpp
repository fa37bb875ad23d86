#pragma once
/// Solid (3D) noise for procedural textures evaluated on surfaces: because it is a function of the 3D point
/// and not of the UV coordinates, maps baked from it have no visible seams across UV chart borders.

#include <cstdint>

#include "core/types.hpp"

namespace forensim {

/// Improved gradient noise (Perlin 2002) on the integer lattice, with a permutation table shuffled from
/// `seed`. evaluate() returns values in about [-1, 1], zero at lattice points, C2-continuous (quintic fade).
class GradientNoise3 {
 public:
  explicit GradientNoise3(std::uint64_t seed);
  /// Noise at `p` (lattice units: one lattice cell per unit).
  double evaluate(const Vec3& p) const;
  /// Fractal sum of `octaves` octaves: frequency doubles and amplitude is multiplied by `persistence` per
  /// octave, normalised by the sum of amplitudes so the range stays about [-1, 1].
  double fractal(const Vec3& p, int octaves, double persistence = 0.5) const;

 private:
  int m_perm[512];
};

}  // namespace forensim
