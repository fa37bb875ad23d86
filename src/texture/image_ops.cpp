#include "texture/image_ops.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {

namespace {

void require_same_size(const Image& a, const Image& b, const char* what) {
  require_input(a.width() == b.width() && a.height() == b.height(), what, "",
                "image sizes differ: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) + " and " +
                    std::to_string(b.width()) + "x" + std::to_string(b.height()));
}

// Runs f(x, y) over every pixel of an image of the given size, rows in parallel.
template <typename F>
void for_each_pixel(int width, int height, const F& f) {
  parallel_for(
      0, static_cast<std::size_t>(height),
      [&](std::size_t y) {
        for (int x = 0; x < width; ++x) f(x, static_cast<int>(y));
      },
      8);
}

float overlay_channel(float a, float b) {
  return a < 0.5f ? 2.0f * a * b : 1.0f - 2.0f * (1.0f - a) * (1.0f - b);
}

}  // namespace

double cubic_interpolate(double v0, double v1, double v2, double v3, double t) {
  const double p = (v3 - v2) - (v0 - v1);
  const double q = (v0 - v1) - p;
  const double r = v2 - v0;
  return ((p * t + q) * t + r) * t + v1;
}

int wrap_pixel_index(long long i, int size, WrapMode wrap) {
  if (wrap == WrapMode::wrap) {
    const long long m = i % size;
    return static_cast<int>(m < 0 ? m + size : m);
  }
  return static_cast<int>(std::clamp<long long>(i, 0, size - 1));
}

float sample_bilinear(const Image& image, double x, double y, int c, WrapMode wrap) {
  if (image.empty() || !std::isfinite(x) || !std::isfinite(y)) return 0.0f;
  return image.sample(x, y, c, wrap);
}

float sample_bicubic(const Image& image, double x, double y, int c, WrapMode wrap) {
  if (image.empty() || !std::isfinite(x) || !std::isfinite(y)) return 0.0f;
  const double limit = 1e9;
  const double fx = std::clamp(x - 0.5, -limit, limit), fy = std::clamp(y - 0.5, -limit, limit);
  const double x1f = std::floor(fx), y1f = std::floor(fy);
  const long long x1 = static_cast<long long>(x1f), y1 = static_cast<long long>(y1f);
  const double tx = fx - x1f, ty = fy - y1f;
  int xs[4];
  for (int k = 0; k < 4; ++k) xs[k] = wrap_pixel_index(x1 - 1 + k, image.width(), wrap);
  double rows[4];
  for (int k = 0; k < 4; ++k) {
    const int yk = wrap_pixel_index(y1 - 1 + k, image.height(), wrap);
    rows[k] = cubic_interpolate(image.at(xs[0], yk, c), image.at(xs[1], yk, c), image.at(xs[2], yk, c),
                                image.at(xs[3], yk, c), tx);
  }
  return static_cast<float>(cubic_interpolate(rows[0], rows[1], rows[2], rows[3], ty));
}

Vec4f blend_multiply(const Vec4f& a, const Vec4f& b) {
  return a.cwiseProduct(b);
}

Vec4f blend_screen(const Vec4f& a, const Vec4f& b) {
  return a + b.cwiseProduct(Vec4f::Ones() - a);
}

Vec4f blend_overlay(const Vec4f& a, const Vec4f& b) {
  return {overlay_channel(a[0], b[0]), overlay_channel(a[1], b[1]), overlay_channel(a[2], b[2]),
          overlay_channel(a[3], b[3])};
}

Vec4f blend_lerp(const Vec4f& a, const Vec4f& b, float t) {
  return a + (b - a) * t;
}

Image blend_images(const Image& a, const Image& b, BlendMode mode) {
  require_same_size(a, b, "blend_images");
  Image out(a.width(), a.height(), std::max(a.channels(), 1), 0.0f, a.encoding());
  if (a.empty()) return out;
  for_each_pixel(a.width(), a.height(), [&](int x, int y) {
    const Vec4f pa = a.rgba(x, y), pb = b.rgba(x, y);
    Vec4f v;
    switch (mode) {
      case BlendMode::multiply:
        v = blend_multiply(pa, pb);
        break;
      case BlendMode::screen:
        v = blend_screen(pa, pb);
        break;
      case BlendMode::overlay:
      default:
        v = blend_overlay(pa, pb);
        break;
    }
    out.set_rgba(x, y, v);
  });
  return out;
}

Image multiply_color(const Image& image, const Vec4f& color) {
  Image out(image.width(), image.height(), std::max(image.channels(), 1), 0.0f, image.encoding());
  if (image.empty()) return out;
  for_each_pixel(image.width(), image.height(),
                 [&](int x, int y) { out.set_rgba(x, y, blend_multiply(image.rgba(x, y), color)); });
  return out;
}

Image lerp_by_mask(const Image& a, const Image& b, const Image& mask) {
  require_same_size(a, b, "lerp_by_mask");
  require_same_size(a, mask, "lerp_by_mask mask");
  Image out(a.width(), a.height(), std::max(a.channels(), 1), 0.0f, a.encoding());
  if (a.empty()) return out;
  for_each_pixel(a.width(), a.height(), [&](int x, int y) {
    const float m = std::clamp(mask.at(x, y, 0), 0.0f, 1.0f);
    out.set_rgba(x, y, blend_lerp(a.rgba(x, y), b.rgba(x, y), m));
  });
  return out;
}

}  // namespace forensim
