#pragma once
/// Text on pictures (captions, legends, landmark labels) with stb_truetype and the DejaVu Sans font
/// found at build time (FORENSIM_FONT_FILE). Text is UTF-8; colours are display (sRGB) values with alpha.

#include <string>

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

enum class TextAlign { left, centre, right };

struct TextMetrics {
  double width = 0;    ///< advance width of the whole string (pixels)
  double ascent = 0;   ///< from the line top to the baseline (pixels)
  double descent = 0;  ///< below the baseline (pixels, positive)
  double line_height() const { return ascent + descent; }
};

/// Size of `text` at a font size of `size_px` pixels (the em height). Throws IoError if the font
/// cannot be loaded.
TextMetrics measure_text(const std::string& text, double size_px);

/// Draws `text` with the top of its line box at y and, after `align`, its left end, centre or right end
/// at x. Returns the drawn width in pixels. Clipped to the image.
double draw_text(Image& image, double x, double y, const std::string& text, double size_px, const Vec4f& colour,
                 TextAlign align = TextAlign::left);

/// draw_text over a halo: the text is first drawn in `halo` shifted by up to `halo_px` in eight
/// directions, so labels stay readable over any picture (landmark names over skin and bone).
double draw_text_with_halo(Image& image, double x, double y, const std::string& text, double size_px,
                           const Vec4f& colour, const Vec4f& halo, double halo_px = 1.5,
                           TextAlign align = TextAlign::left);

}  // namespace forensim
