#include "render/colour_bar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/draw.hpp"
#include "render/text.hpp"

namespace forensim {

std::string format_tick(double value, double step, int decimals) {
  if (decimals < 0) {
    // The fewest decimals that write the step exactly (0.25 -> 2, 0.1 -> 1, 50 -> 0), else three
    // significant digits of the step.
    const double s = std::abs(step);
    decimals = 2;
    if (s > 0 && std::isfinite(s)) {
      decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(s))) + 2, 0, 6);
      for (int d = 0; d <= 4; ++d) {
        const double scaled = s * std::pow(10.0, d);
        if (std::abs(scaled - std::round(scaled)) < 1e-6 * std::max(1.0, scaled)) {
          decimals = d;
          break;
        }
      }
    }
  }
  if (std::abs(value) < 0.5 * std::pow(10.0, -decimals)) value = 0.0;  // no "-0.00"
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  return buffer;
}

namespace {
double font_size(double px) {
  return std::isfinite(px) ? std::clamp(px, 4.0, 200.0) : 16.0;
}
}  // namespace

void draw_colour_bar(Image& image, int x, int y, int width, int height, const ColourBar& bar) {
  const double font = font_size(bar.font_px);
  const std::string heading = bar.unit.empty()    ? bar.title
                              : bar.title.empty() ? "[" + bar.unit + "]"
                                                  : bar.title + " [" + bar.unit + "]";
  int top = y;
  if (!heading.empty()) {
    draw_text(image, x, y, heading, font, bar.text_colour);
    top += static_cast<int>(std::ceil(font * 1.6));
  }
  const int bar_width = std::max(8, std::min(width / 4, static_cast<int>(font * 1.4)));
  const int label_half = static_cast<int>(std::ceil(font * 0.6));
  const int bar_top = top + label_half, bar_bottom = y + height - label_half;
  if (bar_bottom - bar_top < 4) return;
  for (int j = bar_top; j < bar_bottom; ++j) {
    const double t = 1.0 - (j + 0.5 - bar_top) / (bar_bottom - bar_top);
    const Vec3f c = bar.colormap.sample_srgb(t);
    fill_rect(image, x, j, bar_width, 1, Vec4f(c[0], c[1], c[2], 1.0f));
  }
  draw_rect(image, x, bar_top, bar_width, bar_bottom - bar_top, bar.text_colour);
  const int ticks = std::max(2, bar.ticks);
  const double step = (bar.max - bar.min) / (ticks - 1);
  for (int k = 0; k < ticks; ++k) {
    const double value = bar.min + step * k;
    const double t = static_cast<double>(k) / (ticks - 1);
    const int j = static_cast<int>(std::lround(bar_bottom - t * (bar_bottom - bar_top)));
    fill_rect(image, x + bar_width, std::min(j, bar_bottom - 1), 5, 1, bar.text_colour);
    draw_text(image, x + bar_width + 8, j - 0.62 * font, format_tick(value, step, bar.decimals), font, bar.text_colour);
  }
}

Image with_colour_bar(const Image& picture, const ColourBar& bar, const std::optional<Vec4f>& panel) {
  const std::string longest = format_tick(std::abs(bar.max) > std::abs(bar.min) ? bar.max : bar.min,
                                          (bar.max - bar.min) / std::max(1, bar.ticks - 1), bar.decimals);
  const std::string heading = bar.title + (bar.unit.empty() ? "" : " [" + bar.unit + "]");
  const double font = font_size(bar.font_px);
  const double label_width = measure_text("-" + longest, font).width;
  const int bar_width = static_cast<int>(font * 1.4);
  const double content = std::max(measure_text(heading, font).width, bar_width + 8 + label_width);
  const int panel_width = static_cast<int>(std::ceil(std::min(content, 4000.0))) + static_cast<int>(2 * font);
  Image out(picture.width() + panel_width, picture.height(), 4, 0.0f, PixelEncoding::srgb);
  out.fill(panel ? *panel : (picture.empty() ? Vec4f(1, 1, 1, 1) : picture.rgba(0, 0)));
  out.paste(picture, 0, 0);
  const int margin = static_cast<int>(font);
  const int legend_height = std::min(picture.height() - 2 * margin, std::max(120, picture.height() * 2 / 3));
  draw_colour_bar(out, picture.width() + margin / 2, (picture.height() - legend_height) / 2, panel_width - margin,
                  legend_height, bar);
  return out;
}

}  // namespace forensim
