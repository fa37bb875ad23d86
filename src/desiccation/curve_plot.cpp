#include "desiccation/curve_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/colour_bar.hpp"
#include "render/draw.hpp"
#include "render/text.hpp"

namespace forensim {

namespace {

/// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `count` ticks over `span`.
double nice_step(double span, int count) {
  const double raw = span / std::max(count, 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) return m * power;
  return 10.0 * power;
}

const Vec4f palette[] = {{0.12f, 0.47f, 0.71f, 1}, {0.84f, 0.15f, 0.16f, 1}, {0.17f, 0.63f, 0.17f, 1},
                         {1.0f, 0.50f, 0.05f, 1},  {0.58f, 0.40f, 0.74f, 1}, {0.55f, 0.34f, 0.29f, 1},
                         {0.89f, 0.47f, 0.76f, 1}, {0.50f, 0.50f, 0.50f, 1}, {0.74f, 0.74f, 0.13f, 1},
                         {0.09f, 0.75f, 0.81f, 1}};

}  // namespace

Image plot_curves(const std::vector<CurveSeries>& series, const CurvePlotStyle& style,
                  const std::vector<ReferencePoint>& references) {
  Image image(style.width, style.height, 4, 1.0f, PixelEncoding::srgb);
  const Vec4f black(0.1f, 0.1f, 0.1f, 1.0f), grid(0.85f, 0.85f, 0.85f, 1.0f);
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
  for (const CurveSeries& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x_lo = std::min(x_lo, s.x[i]);
      x_hi = std::max(x_hi, s.x[i]);
      y_lo = std::min(y_lo, s.y[i]);
      y_hi = std::max(y_hi, s.y[i]);
    }
  for (const ReferencePoint& r : references) {
    x_lo = std::min(x_lo, r.x);
    x_hi = std::max(x_hi, r.x);
    y_lo = std::min(y_lo, r.y);
    y_hi = std::max(y_hi, r.y);
  }
  if (x_lo > x_hi) x_lo = 0.0, x_hi = 1.0, y_lo = 0.0, y_hi = 1.0;
  if (style.y_min < style.y_max) y_lo = style.y_min, y_hi = style.y_max;
  if (x_hi - x_lo < 1e-12) x_hi = x_lo + 1.0;
  if (y_hi - y_lo < 1e-12) y_hi = y_lo + 1.0;

  const double left = 80, right = style.width - 190.0, top = 50, bottom = style.height - 60.0;
  auto px = [&](double x) { return left + (x - x_lo) / (x_hi - x_lo) * (right - left); };
  auto py = [&](double y) { return bottom - (y - y_lo) / (y_hi - y_lo) * (bottom - top); };

  const double font = 15.0;
  const double x_step = nice_step(x_hi - x_lo, 8), y_step = nice_step(y_hi - y_lo, 6);
  for (double x = std::ceil(x_lo / x_step) * x_step; x <= x_hi + 1e-9 * x_step; x += x_step) {
    draw_line(image, Vec2(px(x), top), Vec2(px(x), bottom), grid, 1.0);
    draw_text(image, px(x), bottom + 6, format_tick(x, x_step, -1), font, black, TextAlign::centre);
  }
  for (double y = std::ceil(y_lo / y_step) * y_step; y <= y_hi + 1e-9 * y_step; y += y_step) {
    draw_line(image, Vec2(left, py(y)), Vec2(right, py(y)), grid, 1.0);
    draw_text(image, left - 8, py(y) - font * 0.6, format_tick(y, y_step, -1), font, black, TextAlign::right);
  }
  draw_line(image, Vec2(left, bottom), Vec2(right, bottom), black, 1.5);
  draw_line(image, Vec2(left, top), Vec2(left, bottom), black, 1.5);
  draw_text(image, 0.5 * (left + right), 12, style.title, 18.0, black, TextAlign::centre);
  draw_text(image, 0.5 * (left + right), bottom + 30, style.x_label, font, black, TextAlign::centre);
  draw_text(image, 8, top - 30, style.y_label, font, black, TextAlign::left);

  for (std::size_t k = 0; k < series.size(); ++k) {
    const CurveSeries& s = series[k];
    const Vec4f colour = palette[k % (sizeof palette / sizeof palette[0])];
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i + 1 < n; ++i)
      draw_line(image, Vec2(px(s.x[i]), py(s.y[i])), Vec2(px(s.x[i + 1]), py(s.y[i + 1])), colour, 2.2);
    if (n == 1) draw_disc(image, Vec2(px(s.x[0]), py(s.y[0])), 3.0, colour);
    const double ly = top + 22.0 * static_cast<double>(k);
    draw_line(image, Vec2(right + 12, ly + 9), Vec2(right + 40, ly + 9), colour, 3.0);
    draw_text(image, right + 46, ly, s.name, font, black, TextAlign::left);
  }
  for (const ReferencePoint& r : references) {
    draw_disc(image, Vec2(px(r.x), py(r.y)), 6.0, Vec4f(0.0f, 0.0f, 0.0f, 1.0f), 0.0);
    draw_text(image, px(r.x) - 8, py(r.y) + 8, r.label, 13.0, black, TextAlign::right);
  }
  return image;
}

}  // namespace forensim
