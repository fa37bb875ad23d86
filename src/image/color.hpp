#pragma once
/// The sRGB transfer curve (IEC 61966-2-1): display-referred 8-bit pictures store sRGB-encoded values,
/// shading and blending work on linear light.

#include "image/image.hpp"

namespace forensim {

/// sRGB-encoded value in [0,1] to linear light (piecewise: linear below 0.04045, else power 2.4).
float srgb_to_linear(float encoded);
/// Linear light to the sRGB encoding; values are clamped to [0,1] first.
float linear_to_srgb(float linear);
/// Applies linear_to_srgb to the colour channels (alpha untouched) of a
/// linear image; returns a copy tagged PixelEncoding::srgb. Images already srgb or data are returned as is.
Image to_srgb(const Image& linear);
/// Inverse of to_srgb: an srgb-tagged image becomes linear; linear and data images are returned as is.
Image to_linear(const Image& srgb);

}  // namespace forensim
