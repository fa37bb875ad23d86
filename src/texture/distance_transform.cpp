#include "texture/distance_transform.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// FH 2012 Algorithm 1 on n samples of f (stride apart in `data`), written back in place; v, z and d are
// scratch of size n, n + 1 and n. Samples at +infinity hold no parabola.
void transform_line(double* data, std::size_t stride, int n, std::vector<int>& v, std::vector<double>& z,
                    std::vector<double>& d) {
  int k = -1;
  for (int q = 0; q < n; ++q) {
    const double fq = data[static_cast<std::size_t>(q) * stride];
    if (fq == infinity) continue;
    double s = -infinity;
    while (k >= 0) {
      const int p = v[static_cast<std::size_t>(k)];
      const double fp = data[static_cast<std::size_t>(p) * stride];
      s = ((fq + static_cast<double>(q) * q) - (fp + static_cast<double>(p) * p)) / (2.0 * (q - p));
      if (s <= z[static_cast<std::size_t>(k)]) {
        --k;
      } else {
        break;
      }
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] = k == 0 ? -infinity : s;
    z[static_cast<std::size_t>(k) + 1] = infinity;
  }
  if (k < 0) return;  // no finite sample: the line stays at +infinity
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<std::size_t>(j) + 1] < q) ++j;
    const int p = v[static_cast<std::size_t>(j)];
    d[static_cast<std::size_t>(q)] = static_cast<double>(q - p) * (q - p) + data[static_cast<std::size_t>(p) * stride];
  }
  for (int q = 0; q < n; ++q) data[static_cast<std::size_t>(q) * stride] = d[static_cast<std::size_t>(q)];
}

Image to_distance_image(const std::vector<double>& squared, int width, int height, double sign) {
  Image out(width, height, 1, 0.0f, PixelEncoding::data);
  float* values = out.data().data();
  parallel_for_chunks(0, squared.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) values[i] = static_cast<float>(sign * std::sqrt(squared[i]));
  });
  return out;
}

}  // namespace

std::vector<std::uint8_t> binary_mask(const Image& mask, float threshold) {
  const std::size_t count = static_cast<std::size_t>(mask.width()) * static_cast<std::size_t>(mask.height());
  std::vector<std::uint8_t> out(count, 0);
  if (count == 0) return out;
  const std::size_t channels = static_cast<std::size_t>(mask.channels());
  const float* values = mask.data().data();
  for (std::size_t i = 0; i < count; ++i) out[i] = values[i * channels] >= threshold ? 1 : 0;
  return out;
}

std::vector<double> squared_distance_transform_1d(const std::vector<double>& f) {
  std::vector<double> out = f;
  const int n = static_cast<int>(f.size());
  std::vector<int> v(f.size());
  std::vector<double> z(f.size() + 1), d(f.size());
  if (n > 0) transform_line(out.data(), 1, n, v, z, d);
  return out;
}

std::vector<double> squared_distance_transform(const std::vector<std::uint8_t>& feature, int width, int height) {
  require_input(width >= 0 && height >= 0, "squared_distance_transform", "size", "must not be negative");
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  require_input(feature.size() == count, "squared_distance_transform", "mask",
                "has " + std::to_string(feature.size()) + " values for " + std::to_string(width) + "x" +
                    std::to_string(height) + " texels");
  std::vector<double> grid(count);
  for (std::size_t i = 0; i < count; ++i) grid[i] = feature[i] ? 0.0 : infinity;
  if (count == 0) return grid;
  const std::size_t w = static_cast<std::size_t>(width);
  // Columns: each is independent. A chunk of up to 16 columns is gathered row by row into contiguous
  // scratch (strided access inside the envelope search is slow), transformed, and scattered back.
  parallel_for_chunks(
      0, w,
      [&](std::size_t begin, std::size_t end) {
        const std::size_t h = static_cast<std::size_t>(height), n = end - begin;
        std::vector<int> v(h);
        std::vector<double> z(h + 1), d(h), columns(n * h);
        for (std::size_t y = 0; y < h; ++y)
          for (std::size_t c = 0; c < n; ++c) columns[c * h + y] = grid[y * w + begin + c];
        for (std::size_t c = 0; c < n; ++c) transform_line(columns.data() + c * h, 1, height, v, z, d);
        for (std::size_t y = 0; y < h; ++y)
          for (std::size_t c = 0; c < n; ++c) grid[y * w + begin + c] = columns[c * h + y];
      },
      16);
  parallel_for_chunks(
      0, static_cast<std::size_t>(height),
      [&](std::size_t begin, std::size_t end) {
        std::vector<int> v(w);
        std::vector<double> z(w + 1), d(w);
        for (std::size_t y = begin; y < end; ++y) transform_line(grid.data() + y * w, 1, width, v, z, d);
      },
      16);
  return grid;
}

Image distance_to_mask(const Image& mask, float threshold) {
  return to_distance_image(squared_distance_transform(binary_mask(mask, threshold), mask.width(), mask.height()),
                           mask.width(), mask.height(), 1.0);
}

Image signed_distance(const Image& mask, float threshold) {
  const std::vector<std::uint8_t> inside = binary_mask(mask, threshold);
  std::vector<std::uint8_t> outside(inside.size());
  for (std::size_t i = 0; i < inside.size(); ++i) outside[i] = inside[i] ? 0 : 1;
  const std::vector<double> to_inside = squared_distance_transform(inside, mask.width(), mask.height());
  const std::vector<double> to_outside = squared_distance_transform(outside, mask.width(), mask.height());
  Image out(mask.width(), mask.height(), 1, 0.0f, PixelEncoding::data);
  float* values = out.data().data();
  parallel_for_chunks(0, inside.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      values[i] =
          inside[i] ? -static_cast<float>(std::sqrt(to_outside[i])) : static_cast<float>(std::sqrt(to_inside[i]));
  });
  return out;
}

}  // namespace forensim
