#pragma once
/// A wound canvas for a shape drawn straight in texture space, without a mesh: a flat patch of skin at a
/// given texel density whose region is the whole texture, with distances in texels through the exact
/// distance transform (the thesis's UV way, Linnenbank 2015 chapter 3.3.3). For benchmarks at the thesis's
/// full-texture scale and for shapes that come as images.

#include <cstdint>

#include "image/image.hpp"
#include "wound/wound_canvas.hpp"

namespace forensim {

/// Canvas of `shape` (1 channel, >= 0.5 inside) over the whole texture at `texels_per_mm` (> 0), with the
/// RGBA skin maps of the shape's size. Throws InputError for mismatched sizes, a bad density or an empty
/// shape.
WoundCanvas make_flat_canvas(const Image& shape, double texels_per_mm, const Image& upper_skin, const Image& lower_skin,
                             std::uint64_t seed);

}  // namespace forensim
