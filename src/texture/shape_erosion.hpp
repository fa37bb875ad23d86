#pragma once
/// Shape texture erosion of the wound thesis (Linnenbank 2015, chapter 3.3.1, Algorithm 3.1): a 1-pixel-high
/// minimum filter whose odd width varies per pixel (eq. 3.1), roughening the edge of a wound shape as if
/// something had scraped over the skin. Widths are in texels: the caller converts from mm on the skin
/// (width_texels = width_mm * texels_per_mm) so that the edge looks the same at any resolution.

#include <cstdint>
#include <vector>

#include "image/image.hpp"

namespace forensim {

/// Eq. 3.1: kernelWidth(m) = m + (m mod 2) + 1, an odd width from a positive random integer m.
int erosion_kernel_width(int m);

/// Per-pixel kernel widths (row-major, width * height): m drawn uniformly from [m_min, m_max] (1 <= m_min
/// <= m_max <= 4096) by hash of (seed, pixel index), then eq. 3.1. (The thesis's "kernel width varying
/// between 3 and 5" and "between 3 and 10" are such ranges of m.) Throws InputError for a bad range.
std::vector<int> random_erosion_widths(int width, int height, int m_min, int m_max, std::uint64_t seed);

/// Direction of the 1-pixel-high kernel: along rows (the thesis's N x 1 kernel) or along columns.
enum class ErosionAxis { x, y };

/// Algorithm 3.1 on channel 0 of `shape`: out(x, y) = min of shape over the widths[y * W + x] pixels centred
/// on (x, y) along the axis; pixels beyond the border count as the highest value (ignored). Returns a
/// single-channel data image. widths must hold width * height odd positive values (InputError otherwise).
Image erode_shape(const Image& shape, const std::vector<int>& widths, ErosionAxis axis = ErosionAxis::x);

/// erode_shape with random_erosion_widths(shape size, m_min, m_max, seed). On a 0/1 shape (a wound mask) the
/// same result in time linear in the texels, widths drawn only near the shape's edges.
Image erode_shape(const Image& shape, int m_min, int m_max, std::uint64_t seed, ErosionAxis axis = ErosionAxis::x);

/// Algorithm 3.1 on one line of a 0/1 mask (values exactly 0 or 1) in time linear in its length:
/// out[i * out_step] = min of in[j * in_step] over the texels j of [0, n) within half of texel i's kernel
/// width, the width drawn as random_erosion_widths draws it for pixel index index0 + i * index_step
/// (texels beyond [0, n) are ignored, as beyond an image's border). erode_shape of a 0/1 image equals this
/// line by line; a caller that needs a few rows of an erosion (a tile) computes just those.
void erode_binary_line(const float* in, std::size_t in_step, int n, int m_min, int m_max, std::uint64_t seed,
                       std::uint64_t index0, std::uint64_t index_step, float* out, std::size_t out_step);

}  // namespace forensim
