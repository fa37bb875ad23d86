#pragma once
/// Tileable 2D lattice noises beyond the wound thesis: gradient (Perlin 2002, quintic fade) and cellular
/// (Worley 1996, distances F1 and F2 to the nearest feature points). Both are periodic: a lattice of
/// `period_x` x `period_y` cells repeats, so a texture covering exactly one period tiles without seams.
/// Coordinates are in lattice cells; lattice values depend only on (seed, cell), so results do not depend
/// on thread count. To keep a look at any resolution, choose the number of cells from the size in mm on the
/// skin (cells = texture size in mm / feature size in mm), not from texels.

#include <cstdint>

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

/// Periodic gradient noise at p (cells), period (period_x, period_y) >= 1 cells: values in about [-1, 1],
/// 0 at lattice points, C2 (quintic fade), noise(p + (period_x, 0)) = noise(p).
double tile_perlin_noise(const Vec2& p, int period_x, int period_y, std::uint64_t seed);

/// Distances (in cells) from p to its nearest (f1) and second nearest (f2) feature point; one jittered
/// feature point per cell, periodic over period_x x period_y cells (>= 1 each). The point of cell (i, j)
/// (wrapped into the period, key = j * period_x + i) lies at (i + hash_uniform(seed, key, 1), j +
/// hash_uniform(seed, key, 2)). f1 <= f2; both continuous.
struct WorleyDistances {
  double f1 = 0.0;
  double f2 = 0.0;
};
WorleyDistances tile_worley_noise(const Vec2& p, int period_x, int period_y, std::uint64_t seed);

/// Which value a Worley image stores.
enum class WorleyFeature { f1, f2, f2_minus_f1 };

/// width x height single-channel data image of fractal periodic Perlin noise remapped to [0, 1]
/// (0.5 + 0.5 n, clamped): `octaves` octaves, octave k with cells_x 2^k x cells_y 2^k cells across the
/// image and amplitude persistence^k, normalised by the sum of amplitudes. Tiles seamlessly over the image.
/// Pixel (x, y) samples at its centre. Throws InputError for sizes or counts out of range.
Image tile_perlin_image(int width, int height, int cells_x, int cells_y, int octaves, double persistence,
                        std::uint64_t seed);

/// width x height single-channel data image of periodic Worley noise over cells_x x cells_y cells across
/// the image (so it tiles): the chosen feature distance in cells, not clamped (f1 is below about 1.1).
Image tile_worley_image(int width, int height, int cells_x, int cells_y, WorleyFeature feature, std::uint64_t seed);

}  // namespace forensim
