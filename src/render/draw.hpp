#pragma once
/// Anti-aliased 2D drawing on display-referred pictures (overlays, legends, sheets). Colours are display
/// (sRGB) values with alpha; coordinates are continuous pixels, (0,0) the top-left corner of the image.

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

/// Blends `colour` over pixel (x, y) with extra coverage `coverage` in [0,1]; ignores pixels outside.
void blend_pixel(Image& image, int x, int y, const Vec4f& colour, float coverage);
/// Line segment from a to b, `width` pixels wide, with round caps.
void draw_line(Image& image, const Vec2& a, const Vec2& b, const Vec4f& colour, double width);
/// Filled disc of `radius` pixels centred at `centre`, with an optional outline ring of `outline_width`.
void draw_disc(Image& image, const Vec2& centre, double radius, const Vec4f& colour, double outline_width = 0.0,
               const Vec4f& outline_colour = Vec4f(0, 0, 0, 1));
/// Filled axis-aligned rectangle [x, x+w) x [y, y+h) in whole pixels.
void fill_rect(Image& image, int x, int y, int w, int h, const Vec4f& colour);
/// One-pixel rectangle outline.
void draw_rect(Image& image, int x, int y, int w, int h, const Vec4f& colour);

}  // namespace forensim
