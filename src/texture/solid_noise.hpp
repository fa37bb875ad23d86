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

/// What WorleyNoise3::evaluate() finds around a point.
struct CellularSample {
  double f1 = 0.0;              ///< distance to the nearest feature point (lattice units)
  double f2 = 0.0;              ///< distance to the second nearest
  std::uint64_t cell = 0;       ///< hash of the nearest feature point's cell: a stable id for per-cell values
  Vec3 nearest = Vec3::Zero();  ///< the nearest feature point
};

/// Cellular noise (Worley 1996): one feature point per lattice cell, jittered uniformly within the cell by
/// `jitter` (0 = cell centres, 1 = anywhere in the cell), from `seed`. The 27 cells around the point are
/// searched (the usual approximation: a nearer point two cells away is rare and only moves F2). Used for pores
/// (F1 dimples), freckles (sparse per-cell spots) and skin cells.
class WorleyNoise3 {
 public:
  explicit WorleyNoise3(std::uint64_t seed, double jitter = 0.9);
  /// F1, F2 and the nearest cell at `p` (lattice units).
  CellularSample evaluate(const Vec3& p) const;
  /// Uniform [0, 1) value attached to a cell id (`channel` selects independent values per cell).
  double cell_value(std::uint64_t cell, std::uint64_t channel = 0) const;

 private:
  Vec3 feature_point(long long x, long long y, long long z, std::uint64_t& cell) const;
  std::uint64_t m_seed;
  double m_jitter;
};

}  // namespace forensim
