#include "image/image.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace forensim {
namespace {

// One output sample of a 1-D resampling: source indices and weights.
struct Taps {
  std::vector<int> first;     // per output: index into index/weight arrays
  std::vector<int> source;    // source pixel index
  std::vector<float> weight;  // weight of that source pixel
};

// Box filter (exact area overlap) when shrinking, bilinear when enlarging or keeping the size.
Taps make_taps(int source_size, int target_size) {
  Taps taps;
  taps.first.reserve(static_cast<std::size_t>(target_size) + 1);
  const double scale = static_cast<double>(source_size) / target_size;
  for (int i = 0; i < target_size; ++i) {
    taps.first.push_back(static_cast<int>(taps.source.size()));
    if (scale > 1.0) {
      const double lo = i * scale, hi = (i + 1) * scale;
      const int a = static_cast<int>(std::floor(lo));
      const int b = std::min(source_size - 1, static_cast<int>(std::ceil(hi)) - 1);
      for (int s = a; s <= b; ++s) {
        const double overlap = std::min(hi, s + 1.0) - std::max(lo, static_cast<double>(s));
        if (overlap <= 0) continue;
        taps.source.push_back(s);
        taps.weight.push_back(static_cast<float>(overlap / scale));
      }
    } else {
      const double x = std::clamp((i + 0.5) * scale - 0.5, 0.0, static_cast<double>(source_size - 1));
      const int a = static_cast<int>(std::floor(x));
      const int b = std::min(a + 1, source_size - 1);
      const float f = static_cast<float>(x - a);
      taps.source.push_back(a);
      taps.weight.push_back(1.0f - f);
      if (b != a) {
        taps.source.push_back(b);
        taps.weight.push_back(f);
      }
    }
  }
  taps.first.push_back(static_cast<int>(taps.source.size()));
  return taps;
}

int wrap_index(int i, int n, WrapMode wrap) {
  if (wrap == WrapMode::clamp) return std::clamp(i, 0, n - 1);
  const int m = i % n;
  return m < 0 ? m + n : m;
}

float luminance(const Vec4f& v) {
  return 0.2126f * v[0] + 0.7152f * v[1] + 0.0722f * v[2];
}

}  // namespace

Image::Image(int width, int height, int channels, float value, PixelEncoding encoding)
    : m_width(width), m_height(height), m_channels(channels), m_encoding(encoding) {
  require_input(width >= 0 && height >= 0, "image", "",
                "negative size " + std::to_string(width) + " x " + std::to_string(height));
  require_input(channels >= 1 && channels <= 4, "image", "", "unsupported channel count " + std::to_string(channels));
  require_input(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) <= max_image_pixels, "image", "",
                "size " + std::to_string(width) + " x " + std::to_string(height) + " exceeds the limit of 2^28 pixels");
  m_data.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(channels),
                value);
}

Vec4f Image::rgba(int x, int y) const {
  const float* p = pixel(x, y);
  switch (m_channels) {
    case 1:
      return {p[0], p[0], p[0], 1.0f};
    case 2:
      return {p[0], p[0], p[0], p[1]};
    case 3:
      return {p[0], p[1], p[2], 1.0f};
    default:
      return {p[0], p[1], p[2], p[3]};
  }
}

void Image::set_rgba(int x, int y, const Vec4f& value) {
  float* p = pixel(x, y);
  switch (m_channels) {
    case 1:
      p[0] = luminance(value);
      break;
    case 2:
      p[0] = luminance(value);
      p[1] = value[3];
      break;
    case 3:
      for (int c = 0; c < 3; ++c) p[c] = value[c];
      break;
    default:
      for (int c = 0; c < 4; ++c) p[c] = value[c];
  }
}

void Image::fill(float value) {
  std::fill(m_data.begin(), m_data.end(), value);
}

void Image::fill(const Vec4f& value) {
  for (int y = 0; y < m_height; ++y)
    for (int x = 0; x < m_width; ++x) set_rgba(x, y, value);
}

float Image::sample(double x, double y, int c, WrapMode wrap) const {
  if (empty()) return 0.0f;
  const double fx = x - 0.5, fy = y - 0.5;
  const double x0f = std::floor(fx), y0f = std::floor(fy);
  // Keep far-away coordinates finite and in int range before converting.
  const double limit = 1e9;
  const int x0 = static_cast<int>(std::clamp(x0f, -limit, limit));
  const int y0 = static_cast<int>(std::clamp(y0f, -limit, limit));
  const float tx = static_cast<float>(fx - x0f), ty = static_cast<float>(fy - y0f);
  const int xa = wrap_index(x0, m_width, wrap), xb = wrap_index(x0 + 1, m_width, wrap);
  const int ya = wrap_index(y0, m_height, wrap), yb = wrap_index(y0 + 1, m_height, wrap);
  const float top = at(xa, ya, c) * (1 - tx) + at(xb, ya, c) * tx;
  const float bottom = at(xa, yb, c) * (1 - tx) + at(xb, yb, c) * tx;
  return top * (1 - ty) + bottom * ty;
}

Vec4f Image::sample_uv(const Vec2& uv, WrapMode wrap) const {
  if (empty() || !std::isfinite(uv[0]) || !std::isfinite(uv[1])) return {0, 0, 0, 1};
  const double x = uv[0] * m_width, y = (1.0 - uv[1]) * m_height;
  Vec4f v;
  float values[4] = {0, 0, 0, 1};
  for (int c = 0; c < m_channels; ++c) values[c] = sample(x, y, c, wrap);
  switch (m_channels) {
    case 1:
      v = {values[0], values[0], values[0], 1.0f};
      break;
    case 2:
      v = {values[0], values[0], values[0], values[1]};
      break;
    case 3:
      v = {values[0], values[1], values[2], 1.0f};
      break;
    default:
      v = {values[0], values[1], values[2], values[3]};
  }
  return v;
}

Image Image::crop(int x, int y, int w, int h) const {
  const int x0 = std::clamp(x, 0, m_width), y0 = std::clamp(y, 0, m_height);
  const int x1 = std::clamp(x + std::max(w, 0), 0, m_width), y1 = std::clamp(y + std::max(h, 0), 0, m_height);
  Image out(x1 - x0, y1 - y0, m_channels, 0.0f, m_encoding);
  for (int j = y0; j < y1; ++j)
    std::copy(pixel(x0, j), pixel(x0, j) + static_cast<std::ptrdiff_t>(x1 - x0) * m_channels, out.pixel(0, j - y0));
  return out;
}

void Image::paste(const Image& source, int x, int y, bool blend) {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = std::min(x + source.width(), m_width), y1 = std::min(y + source.height(), m_height);
  for (int j = y0; j < y1; ++j) {
    for (int i = x0; i < x1; ++i) {
      const Vec4f s = source.rgba(i - x, j - y);
      if (!blend) {
        if (source.channels() == m_channels) {
          std::copy(source.pixel(i - x, j - y), source.pixel(i - x, j - y) + m_channels, pixel(i, j));
        } else {
          set_rgba(i, j, s);
        }
        continue;
      }
      const Vec4f d = rgba(i, j);
      const float a = s[3];
      Vec4f o;
      o.head<3>() = s.head<3>() * a + d.head<3>() * (1 - a);
      o[3] = a + d[3] * (1 - a);
      set_rgba(i, j, o);
    }
  }
}

Image Image::resized(int w, int h) const {
  require_input(w > 0 && h > 0, "image", "", "resize to an empty size");
  Image out(w, h, m_channels, 0.0f, m_encoding);
  if (empty()) return out;
  const Taps tx = make_taps(m_width, w), ty = make_taps(m_height, h);
  Image horizontal(w, m_height, m_channels, 0.0f, m_encoding);
  for (int j = 0; j < m_height; ++j)
    for (int i = 0; i < w; ++i)
      for (int k = tx.first[i]; k < tx.first[i + 1]; ++k)
        for (int c = 0; c < m_channels; ++c) horizontal.at(i, j, c) += tx.weight[k] * at(tx.source[k], j, c);
  for (int j = 0; j < h; ++j)
    for (int k = ty.first[j]; k < ty.first[j + 1]; ++k)
      for (int i = 0; i < w; ++i)
        for (int c = 0; c < m_channels; ++c) out.at(i, j, c) += ty.weight[k] * horizontal.at(i, ty.source[k], c);
  return out;
}

Image Image::with_channels(int channels) const {
  Image out(m_width, m_height, channels, 0.0f, m_encoding);
  for (int y = 0; y < m_height; ++y)
    for (int x = 0; x < m_width; ++x) out.set_rgba(x, y, rgba(x, y));
  return out;
}

}  // namespace forensim
