#pragma once
/// Image helpers for the wound texture techniques (Linnenbank 2015, chapters 3 and 4): the cubic of
/// eq. 3.4, bicubic and bilinear sampling with clamp or wrap, and the blend modes the key positions use
/// (multiply, screen = eq. 4.7, overlay, lerp by a mask = eqs. 4.5 and 4.6). Images follow image/image.hpp:
/// rows top to bottom, continuous pixel coordinates with pixel centres at i + 0.5.

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

/// Cubic interpolation of eq. 3.4 between v1 (t = 0) and v2 (t = 1), with v0 and v3 the outer neighbours:
/// p = (v3 - v2) - (v0 - v1), q = (v0 - v1) - p, r = v2 - v0, result p t^3 + q t^2 + r t + v1. It may
/// overshoot [min(v), max(v)] between samples.
double cubic_interpolate(double v0, double v1, double v2, double v3, double t);

/// Bilinear sample of channel c at continuous pixel coordinates (x, y) (same as Image::sample).
float sample_bilinear(const Image& image, double x, double y, int c, WrapMode wrap = WrapMode::clamp);

/// Bicubic sample of channel c at continuous pixel coordinates (x, y), pixel centres at i + 0.5: the 4 x 4
/// neighbouring pixels combined with the cubic of eq. 3.4, first along rows then along the column
/// (Algorithm 3.2, lines 15 to 19). Equals the pixel value at pixel centres. Returns 0 for an empty image
/// or non-finite coordinates.
float sample_bicubic(const Image& image, double x, double y, int c, WrapMode wrap = WrapMode::clamp);

/// Index of pixel i in [0, size) for the wrap mode (clamp to the edge or wrap around); size > 0.
int wrap_pixel_index(long long i, int size, WrapMode wrap);

/// Per-channel blend of two colours (RGBA, values in [0, 1] for screen and overlay).
Vec4f blend_multiply(const Vec4f& a, const Vec4f& b);
/// Screen: 1 - (1 - a)(1 - b) = a + b (1 - a); the thesis's eq. 4.7 (innerColor + gradientColor (white -
/// innerColor)) is screen(inner, gradient).
Vec4f blend_screen(const Vec4f& a, const Vec4f& b);
/// Overlay (base a, layer b): 2ab where a < 0.5, else 1 - 2(1 - a)(1 - b), per channel.
Vec4f blend_overlay(const Vec4f& a, const Vec4f& b);
/// Linear interpolation a (1 - t) + b t, the thesis's Lerp (Algorithms 3.4 and 4.4).
Vec4f blend_lerp(const Vec4f& a, const Vec4f& b, float t);

/// Blend modes of blend_images.
enum class BlendMode { multiply, screen, overlay };

/// Pixel-wise blend of two images of the same size: result(p) = mode(a(p), b(p)) on RGBA values (grey is
/// replicated, see Image::rgba), written with a's channel count and encoding. Throws InputError when the
/// sizes differ.
Image blend_images(const Image& a, const Image& b, BlendMode mode);
/// Pixel-wise multiply by a constant colour (e.g. the thesis's wound red (0.79, 0, 0) on the lower skin).
Image multiply_color(const Image& image, const Vec4f& color);
/// Pixel-wise a (1 - m) + b m with m the first channel of `mask` (clamped to [0, 1]); eqs. 4.5 and 4.6 are
/// lerp_by_mask(upper, lower, noise) and lerp_by_mask(lowerWound, speckle, speckle red). All three images
/// the same size (InputError otherwise); the result has a's channel count and encoding.
Image lerp_by_mask(const Image& a, const Image& b, const Image& mask);

}  // namespace forensim
