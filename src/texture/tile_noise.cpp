#include "texture/tile_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"

namespace forensim {

namespace {

constexpr double two_pi = 6.283185307179586;

long long wrap_cell(long long i, int period) {
  const long long m = i % period;
  return m < 0 ? m + period : m;
}

std::uint64_t cell_key(long long ix, long long iy, int period_x, int period_y) {
  return static_cast<std::uint64_t>(wrap_cell(iy, period_y)) * static_cast<std::uint64_t>(period_x) +
         static_cast<std::uint64_t>(wrap_cell(ix, period_x));
}

double fade(double t) {
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// 256 unit gradients evenly spread over the circle; a lattice point picks one by hash.
struct GradientTable {
  double x[256], y[256];
  GradientTable() {
    for (int i = 0; i < 256; ++i) {
      x[i] = std::cos(two_pi * (i + 0.5) / 256.0);
      y[i] = std::sin(two_pi * (i + 0.5) / 256.0);
    }
  }
};

// Unit gradient of lattice point (ix, iy), wrapped into the period.
void lattice_gradient(long long ix, long long iy, int period_x, int period_y, std::uint64_t seed, double& gx,
                      double& gy) {
  static const GradientTable table;
  const std::size_t g =
      static_cast<std::size_t>(mix64(mix64(seed ^ 0x9E37ull) + cell_key(ix, iy, period_x, period_y)) >> 56);
  gx = table.x[g];
  gy = table.y[g];
}

// The four corner gradients of one lattice cell, so that texels in the same cell share the hashing.
struct PerlinCell {
  long long ix = 0, iy = 0;
  bool valid = false;
  double gx[4], gy[4];  // corners (0,0), (1,0), (0,1), (1,1)

  void load(long long cx, long long cy, int period_x, int period_y, std::uint64_t seed) {
    ix = cx;
    iy = cy;
    valid = true;
    for (int c = 0; c < 4; ++c) lattice_gradient(cx + (c & 1), cy + (c >> 1), period_x, period_y, seed, gx[c], gy[c]);
  }
  // Noise at offset (fx, fy) in [0, 1)^2 inside the cell.
  double evaluate(double fx, double fy) const {
    const double n00 = gx[0] * fx + gy[0] * fy;
    const double n10 = gx[1] * (fx - 1.0) + gy[1] * fy;
    const double n01 = gx[2] * fx + gy[2] * (fy - 1.0);
    const double n11 = gx[3] * (fx - 1.0) + gy[3] * (fy - 1.0);
    const double u = fade(fx), v = fade(fy);
    const double a = n00 + (n10 - n00) * u, b = n01 + (n11 - n01) * u;
    // Unit gradients give |n| <= sqrt(2)/2; scale to about [-1, 1].
    return 1.4142135623730951 * (a + (b - a) * v);
  }
};

// Feature points of the 5 x 5 cells around one cell, relative to that cell's corner.
struct WorleyCell {
  long long ix = 0, iy = 0;
  bool valid = false;
  double px[25], py[25];

  void load(long long cx, long long cy, int period_x, int period_y, std::uint64_t seed) {
    ix = cx;
    iy = cy;
    valid = true;
    int n = 0;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx, ++n) {
        const std::uint64_t key = cell_key(cx + dx, cy + dy, period_x, period_y);
        px[n] = dx + hash_uniform(seed, key, 1);
        py[n] = dy + hash_uniform(seed, key, 2);
      }
  }
  // A feature point lies in every cell, so the two nearest are within the 5 x 5 neighbourhood.
  WorleyDistances evaluate(double fx, double fy) const {
    double d1 = std::numeric_limits<double>::infinity(), d2 = d1;
    for (int n = 0; n < 25; ++n) {
      const double d = (px[n] - fx) * (px[n] - fx) + (py[n] - fy) * (py[n] - fy);
      if (d < d1) {
        d2 = d1;
        d1 = d;
      } else if (d < d2) {
        d2 = d;
      }
    }
    return {std::sqrt(d1), std::sqrt(d2)};
  }
};

void require_period(int period_x, int period_y, const char* what) {
  require_input(period_x >= 1 && period_y >= 1, what, "period", "must be at least one cell in x and y");
}

// Cell coordinate of a finite p, kept in a safe integer range.
long long cell_floor(double v) {
  return static_cast<long long>(std::floor(std::clamp(v, -1e15, 1e15)));
}

void require_image(int width, int height, int cells_x, int cells_y, const char* what) {
  require_input(width >= 0 && height >= 0, what, "size", "must not be negative");
  require_input(cells_x >= 1 && cells_y >= 1 && cells_x <= (1 << 20) && cells_y <= (1 << 20), what, "cells",
                "must be in 1..2^20 in x and y");
}

}  // namespace

double tile_perlin_noise(const Vec2& p, int period_x, int period_y, std::uint64_t seed) {
  require_period(period_x, period_y, "tile_perlin_noise");
  if (!std::isfinite(p[0]) || !std::isfinite(p[1])) return 0.0;
  PerlinCell cell;
  cell.load(cell_floor(p[0]), cell_floor(p[1]), period_x, period_y, seed);
  return cell.evaluate(p[0] - static_cast<double>(cell.ix), p[1] - static_cast<double>(cell.iy));
}

WorleyDistances tile_worley_noise(const Vec2& p, int period_x, int period_y, std::uint64_t seed) {
  require_period(period_x, period_y, "tile_worley_noise");
  if (!std::isfinite(p[0]) || !std::isfinite(p[1])) return {};
  WorleyCell cell;
  cell.load(cell_floor(p[0]), cell_floor(p[1]), period_x, period_y, seed);
  return cell.evaluate(p[0] - static_cast<double>(cell.ix), p[1] - static_cast<double>(cell.iy));
}

Image tile_perlin_image(int width, int height, int cells_x, int cells_y, int octaves, double persistence,
                        std::uint64_t seed) {
  require_image(width, height, cells_x, cells_y, "tile_perlin_image");
  require_input(octaves >= 1 && octaves <= 20, "tile_perlin_image", "octaves", "must be in 1..20");
  require_input(std::isfinite(persistence) && persistence > 0.0, "tile_perlin_image", "persistence",
                "must be a finite positive number");
  Image image(width, height, 1, 0.0f, PixelEncoding::data);
  if (image.empty()) return image;
  double total = 0.0, amplitude = 1.0;
  for (int k = 0; k < octaves; ++k, amplitude *= persistence) total += amplitude;
  parallel_for(
      0, static_cast<std::size_t>(height),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        std::vector<PerlinCell> cells(static_cast<std::size_t>(octaves));  // last cell per octave
        for (int x = 0; x < width; ++x) {
          double sum = 0.0, a = 1.0;
          for (int k = 0; k < octaves; ++k, a *= persistence) {
            const long long scale = 1LL << k;
            const long long px = cells_x * scale, py = cells_y * scale;
            if (px > (1 << 30) || py > (1 << 30)) break;
            const Vec2 p((x + 0.5) * static_cast<double>(px) / width, (y + 0.5) * static_cast<double>(py) / height);
            const long long ix = cell_floor(p[0]), iy = cell_floor(p[1]);
            PerlinCell& cell = cells[static_cast<std::size_t>(k)];
            if (!cell.valid || cell.ix != ix || cell.iy != iy)
              cell.load(ix, iy, static_cast<int>(px), static_cast<int>(py), seed + static_cast<std::uint64_t>(k));
            sum += a * cell.evaluate(p[0] - static_cast<double>(ix), p[1] - static_cast<double>(iy));
          }
          image.at(x, y) = static_cast<float>(std::clamp(0.5 + 0.5 * sum / total, 0.0, 1.0));
        }
      },
      4);
  return image;
}

Image tile_worley_image(int width, int height, int cells_x, int cells_y, WorleyFeature feature, std::uint64_t seed) {
  require_image(width, height, cells_x, cells_y, "tile_worley_image");
  Image image(width, height, 1, 0.0f, PixelEncoding::data);
  if (image.empty()) return image;
  parallel_for(
      0, static_cast<std::size_t>(height),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        WorleyCell cell;
        for (int x = 0; x < width; ++x) {
          const Vec2 p((x + 0.5) * cells_x / width, (y + 0.5) * cells_y / height);
          const long long ix = cell_floor(p[0]), iy = cell_floor(p[1]);
          if (!cell.valid || cell.ix != ix || cell.iy != iy) cell.load(ix, iy, cells_x, cells_y, seed);
          const WorleyDistances d = cell.evaluate(p[0] - static_cast<double>(ix), p[1] - static_cast<double>(iy));
          const double v = feature == WorleyFeature::f1 ? d.f1 : feature == WorleyFeature::f2 ? d.f2 : d.f2 - d.f1;
          image.at(x, y) = static_cast<float>(v);
        }
      },
      4);
  return image;
}

}  // namespace forensim
