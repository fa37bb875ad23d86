#pragma once
/// Colour-bar legends for false-colour pictures (moisture, tissue depth, error maps): the colormap as a
/// bar with its minimum, maximum and tick values, a title and a unit.

#include <optional>
#include <string>

#include "core/types.hpp"
#include "image/colormap.hpp"
#include "image/image.hpp"

namespace forensim {

struct ColourBar {
  Colormap colormap{ColormapName::viridis};
  double min = 0.0, max = 1.0;  ///< values at the bar's ends (min at the bottom)
  int ticks = 5;                ///< labelled values including both ends (>= 2)
  std::string title;            ///< e.g. "moisture"
  std::string unit;             ///< e.g. "kg/kg" or "mm"; shown after the title in brackets
  int decimals = -1;            ///< digits after the decimal point; -1 chooses from the range
  double font_px = 16.0;
  Vec4f text_colour = Vec4f(0.08f, 0.08f, 0.08f, 1.0f);  ///< display (sRGB) colour
};

/// Draws a vertical legend into the rectangle [x, x+width) x [y, y+height) of a display-referred picture:
/// title (and unit) on top, the bar below on the left, tick labels to its right.
void draw_colour_bar(Image& image, int x, int y, int width, int height, const ColourBar& bar);
/// The picture widened on the right by a legend panel of the picture's height, filled with `panel`
/// (by default the colour of the picture's top-left pixel, so the panel continues its background).
Image with_colour_bar(const Image& picture, const ColourBar& bar, const std::optional<Vec4f>& panel = std::nullopt);
/// Tick label text for `value` with `decimals` digits (-1: chosen so neighbouring ticks differ).
std::string format_tick(double value, double step, int decimals);

}  // namespace forensim
