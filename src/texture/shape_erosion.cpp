#include "texture/shape_erosion.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"

namespace forensim {

int erosion_kernel_width(int m) {
  return m + (m % 2) + 1;
}

std::vector<int> random_erosion_widths(int width, int height, int m_min, int m_max, std::uint64_t seed) {
  require_input(width >= 0 && height >= 0, "random_erosion_widths", "size", "must not be negative");
  require_input(m_min >= 1 && m_min <= m_max && m_max <= 4096, "random_erosion_widths", "range",
                "needs 1 <= m_min <= m_max <= 4096, got " + std::to_string(m_min) + ".." + std::to_string(m_max));
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  require_input(count <= max_image_pixels, "random_erosion_widths", "size", "more pixels than an image may have");
  std::vector<int> widths(count);
  const int span = m_max - m_min + 1;
  parallel_for_chunks(0, count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const int m = m_min + std::min(span - 1, static_cast<int>(hash_uniform(seed, i) * span));
      widths[i] = erosion_kernel_width(m);
    }
  });
  return widths;
}

Image erode_shape(const Image& shape, const std::vector<int>& widths, ErosionAxis axis) {
  const int w = shape.width(), h = shape.height();
  const std::size_t count = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  require_input(widths.size() == count, "erode_shape", "widths",
                "needs " + std::to_string(count) + " widths, has " + std::to_string(widths.size()));
  for (std::size_t i = 0; i < count; ++i)
    require_input(widths[i] >= 1 && widths[i] % 2 == 1, "erode_shape", "width " + std::to_string(i),
                  "must be odd and positive, is " + std::to_string(widths[i]));
  Image out(w, h, 1, 0.0f, PixelEncoding::data);
  if (shape.empty()) return out;
  parallel_for(
      0, static_cast<std::size_t>(h),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        for (int x = 0; x < w; ++x) {
          const int edge =
              widths[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] / 2;
          float value = std::numeric_limits<float>::max();  // line 2: highest colour value
          if (axis == ErosionAxis::x) {
            const int lo = std::max(0, x - edge), hi = std::min(w - 1, x + edge);
            for (int k = lo; k <= hi; ++k) value = std::min(value, shape.at(k, y, 0));
          } else {
            const int lo = std::max(0, y - edge), hi = std::min(h - 1, y + edge);
            for (int k = lo; k <= hi; ++k) value = std::min(value, shape.at(x, k, 0));
          }
          out.at(x, y) = value;
        }
      },
      4);
  return out;
}

namespace {

bool is_binary(const Image& shape) {
  if (shape.channels() != 1) return false;
  for (float v : shape.data())
    if (v != 0.0f && v != 1.0f) return false;
  return true;
}

Image erode_binary(const Image& shape, int m_min, int m_max, std::uint64_t seed, ErosionAxis axis) {
  const int w = shape.width(), h = shape.height();
  Image out(w, h, 1, 0.0f, PixelEncoding::data);
  const bool along_x = axis == ErosionAxis::x;
  const int lines = along_x ? h : w, length = along_x ? w : h;
  const std::size_t step = along_x ? 1 : static_cast<std::size_t>(w);
  const float* in = shape.data().data();
  float* o = out.data().data();
  parallel_for(
      0, static_cast<std::size_t>(lines),
      [&](std::size_t line) {
        const std::size_t first = along_x ? line * static_cast<std::size_t>(w) : line;
        erode_binary_line(in + first, step, length, m_min, m_max, seed, first, step, o + first, step);
      },
      4);
  return out;
}

}  // namespace

void erode_binary_line(const float* in, std::size_t in_step, int n, int m_min, int m_max, std::uint64_t seed,
                       std::uint64_t index0, std::uint64_t index_step, float* out, std::size_t out_step) {
  // The minimum over a window of a 0/1 line is 0 exactly when a 0 lies in it, so a texel is 0 when its
  // nearest 0 is within half its kernel width; widths are drawn only for texels whose nearest 0 is within
  // the largest half-width.
  if (n <= 0) return;
  const int span = m_max - m_min + 1;
  const int max_edge = erosion_kernel_width(m_max) / 2;
  thread_local std::vector<int> right;
  right.resize(static_cast<std::size_t>(n));
  constexpr int far = std::numeric_limits<int>::max() / 2;
  int next = far;  // distance to the nearest 0 at or after i
  for (int i = n - 1; i >= 0; --i) {
    next = in[static_cast<std::size_t>(i) * in_step] == 0.0f ? 0 : std::min(next + 1, far);
    right[static_cast<std::size_t>(i)] = next;
  }
  int previous = far;  // distance to the nearest 0 at or before i
  for (int i = 0; i < n; ++i) {
    previous = in[static_cast<std::size_t>(i) * in_step] == 0.0f ? 0 : std::min(previous + 1, far);
    const int nearest = std::min(previous, right[static_cast<std::size_t>(i)]);
    float value = 1.0f;
    if (nearest == 0) {
      value = 0.0f;
    } else if (nearest <= max_edge) {
      const std::uint64_t index = index0 + static_cast<std::uint64_t>(i) * index_step;
      const int m = m_min + std::min(span - 1, static_cast<int>(hash_uniform(seed, index) * span));
      if (nearest <= erosion_kernel_width(m) / 2) value = 0.0f;
    }
    out[static_cast<std::size_t>(i) * out_step] = value;
  }
}

Image erode_shape(const Image& shape, int m_min, int m_max, std::uint64_t seed, ErosionAxis axis) {
  if (!is_binary(shape)) {
    return erode_shape(shape, random_erosion_widths(shape.width(), shape.height(), m_min, m_max, seed), axis);
  }
  require_input(m_min >= 1 && m_min <= m_max && m_max <= 4096, "random_erosion_widths", "range",
                "needs 1 <= m_min <= m_max <= 4096, got " + std::to_string(m_min) + ".." + std::to_string(m_max));
  return erode_binary(shape, m_min, m_max, seed, axis);
}

}  // namespace forensim
