#pragma once
/// Tangent-space normal maps from height (displacement) maps, for wound scabs and any baked relief: the
/// slope of the height field by central differences, in millimetres of height per millimetre on the skin,
/// so a map looks the same at any texture resolution.

#include "image/image.hpp"

namespace forensim {

/// Normal map of `height_mm` (channel 0, heights in mm along the surface normal; rows top to bottom, v up):
/// n = normalize(-strength dh/du_mm, -strength dh/dv_mm, 1) with dh/du_mm = (h(x+1) - h(x-1)) texels_per_mm / 2
/// (clamped at the borders) and v pointing up the image (dh/dv = (h(y-1) - h(y+1)) texels_per_mm / 2).
/// Written as an RGB data image with values n * 0.5 + 0.5 (OpenGL/glTF convention: green = +v). Rows in
/// parallel. Throws InputError when texels_per_mm <= 0 or is not finite.
Image normal_from_height(const Image& height_mm, double texels_per_mm, double strength = 1.0);

}  // namespace forensim
