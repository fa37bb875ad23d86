#pragma once
/// Exact Euclidean distance transform of binary masks (Felzenszwalb & Huttenlocher, "Distance transforms of
/// sampled functions", Theory of Computing 8, 2012): the 1-D lower envelope of parabolas applied to the
/// columns and then to the rows, O(pixels), columns and rows in parallel. Distances are in texels between
/// texel centres; the caller converts to mm (mm = texels / texels_per_mm). The results equal the brute-force
/// minimum over all texels exactly (squared distances are integers, exact in double).

#include <cstdint>
#include <vector>

#include "image/image.hpp"

namespace forensim {

/// Binary mask of channel 0: 1 where value >= threshold, else 0 (row-major, width * height).
std::vector<std::uint8_t> binary_mask(const Image& mask, float threshold = 0.5f);

/// Squared distance from every texel to the nearest texel with feature != 0 (row-major, width * height,
/// (dx^2 + dy^2) in texels^2); +infinity everywhere when there is no feature texel. Throws InputError when
/// feature.size() != width * height.
std::vector<double> squared_distance_transform(const std::vector<std::uint8_t>& feature, int width, int height);

/// 1-D squared distance transform of a sampled function (FH 2012, Algorithm 1): out[q] = min_p (q - p)^2
/// + f[p]; f may hold +infinity. Exposed for tests and for anisotropic uses.
std::vector<double> squared_distance_transform_1d(const std::vector<double>& f);

/// Unsigned distance image: for each texel, the distance in texels to the nearest texel inside the mask
/// (channel 0 >= threshold); 0 inside. +infinity where the mask is empty. Single-channel data image.
Image distance_to_mask(const Image& mask, float threshold = 0.5f);

/// Signed distance image: outside texels hold +distance to the nearest inside texel, inside texels
/// -distance to the nearest outside texel (so |value| >= 1 everywhere next to the border). +/-infinity
/// where the other side is empty. Single-channel data image.
Image signed_distance(const Image& mask, float threshold = 0.5f);

}  // namespace forensim
