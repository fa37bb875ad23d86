#include "render/draw.hpp"

#include <algorithm>
#include <cmath>

namespace forensim {
namespace {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Whole pixels [first, last) covering [lo, hi] clipped to [0, size); false when none (also for NaN).
bool pixel_span(double lo, double hi, int size, int* first, int* last) {
  lo = std::max(lo, 0.0);
  hi = std::min(hi, static_cast<double>(size));
  if (!(lo < hi)) return false;
  *first = static_cast<int>(std::floor(lo));
  *last = std::min(size, static_cast<int>(std::ceil(hi)));
  return *first < *last;
}

}  // namespace

void blend_pixel(Image& image, int x, int y, const Vec4f& colour, float coverage) {
  if (x < 0 || y < 0 || x >= image.width() || y >= image.height()) return;
  const float a = std::clamp(colour[3] * coverage, 0.0f, 1.0f);
  if (a <= 0.0f) return;
  const Vec4f d = image.rgba(x, y);
  Vec4f o;
  o.head<3>() = colour.head<3>() * a + d.head<3>() * (1 - a);
  o[3] = a + d[3] * (1 - a);
  image.set_rgba(x, y, o);
}

void draw_line(Image& image, const Vec2& a, const Vec2& b, const Vec4f& colour, double width) {
  if (!a.allFinite() || !b.allFinite() || !(width > 0)) return;
  const double r = 0.5 * width;
  int x0, x1, y0, y1;
  if (!pixel_span(std::min(a[0], b[0]) - r - 1, std::max(a[0], b[0]) + r + 1, image.width(), &x0, &x1) ||
      !pixel_span(std::min(a[1], b[1]) - r - 1, std::max(a[1], b[1]) + r + 1, image.height(), &y0, &y1))
    return;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const double d = segment_distance(Vec2(x + 0.5, y + 0.5), a, b);
      const double coverage = std::clamp(r + 0.5 - d, 0.0, 1.0);
      if (coverage > 0) blend_pixel(image, x, y, colour, static_cast<float>(coverage));
    }
}

void draw_disc(Image& image, const Vec2& centre, double radius, const Vec4f& colour, double outline_width,
               const Vec4f& outline_colour) {
  if (!centre.allFinite() || !(radius > 0)) return;
  const double outer = radius + std::max(0.0, outline_width);
  int x0, x1, y0, y1;
  if (!pixel_span(centre[0] - outer - 1, centre[0] + outer + 1, image.width(), &x0, &x1) ||
      !pixel_span(centre[1] - outer - 1, centre[1] + outer + 1, image.height(), &y0, &y1))
    return;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const double d = (Vec2(x + 0.5, y + 0.5) - centre).norm();
      if (outline_width > 0) {
        const double c = std::clamp(outer + 0.5 - d, 0.0, 1.0);
        if (c > 0) blend_pixel(image, x, y, outline_colour, static_cast<float>(c));
      }
      const double c = std::clamp(radius + 0.5 - d, 0.0, 1.0);
      if (c > 0) blend_pixel(image, x, y, colour, static_cast<float>(c));
    }
}

void fill_rect(Image& image, int x, int y, int w, int h, const Vec4f& colour) {
  for (int j = std::max(0, y); j < std::min(image.height(), y + h); ++j)
    for (int i = std::max(0, x); i < std::min(image.width(), x + w); ++i) blend_pixel(image, i, j, colour, 1.0f);
}

void draw_rect(Image& image, int x, int y, int w, int h, const Vec4f& colour) {
  fill_rect(image, x, y, w, 1, colour);
  fill_rect(image, x, y + h - 1, w, 1, colour);
  fill_rect(image, x, y + 1, 1, h - 2, colour);
  fill_rect(image, x + w - 1, y + 1, 1, h - 2, colour);
}

}  // namespace forensim
