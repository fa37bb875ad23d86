#include "render/text.hpp"

#include <stb_truetype.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "render/draw.hpp"

#ifndef FORENSIM_FONT_FILE
#define FORENSIM_FONT_FILE "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#endif

namespace forensim {
namespace {

// The font is read once and kept for the process; stbtt_fontinfo only reads from `bytes`.
struct Font {
  std::string bytes;
  stbtt_fontinfo info{};
};

const Font& font() {
  static Font f;
  static std::once_flag once;
  static std::string failure;
  std::call_once(once, [] {
    try {
      f.bytes = read_file(FORENSIM_FONT_FILE, std::size_t{64} << 20);
      const auto* data = reinterpret_cast<const unsigned char*>(f.bytes.data());
      const int offset = stbtt_GetFontOffsetForIndex(data, 0);
      if (offset < 0 || !stbtt_InitFont(&f.info, data, offset)) failure = "not a TrueType font";
    } catch (const std::exception& e) {
      failure = e.what();
    }
  });
  if (!failure.empty()) throw IoError(FORENSIM_FONT_FILE, "cannot load font: " + failure);
  return f;
}

// Decodes UTF-8; malformed bytes become U+FFFD.
std::vector<int> decode_utf8(const std::string& text) {
  std::vector<int> out;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    int len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    if (len == 0 || i + static_cast<std::size_t>(len) > text.size()) {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    int code = len == 1 ? c : c & (0x7F >> len);
    bool ok = true;
    for (int k = 1; k < len; ++k) {
      const auto d = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
      if ((d >> 6) != 2) ok = false;
      code = (code << 6) | (d & 0x3F);
    }
    out.push_back(ok ? code : 0xFFFD);
    i += ok ? static_cast<std::size_t>(len) : 1;
  }
  return out;
}

}  // namespace

TextMetrics measure_text(const std::string& text, double size_px) {
  const Font& f = font();
  const float scale = stbtt_ScaleForMappingEmToPixels(&f.info, static_cast<float>(size_px));
  int ascent, descent, gap;
  stbtt_GetFontVMetrics(&f.info, &ascent, &descent, &gap);
  TextMetrics m;
  m.ascent = ascent * scale;
  m.descent = -descent * scale;
  const std::vector<int> codes = decode_utf8(text);
  double x = 0;
  for (std::size_t i = 0; i < codes.size(); ++i) {
    int advance, bearing;
    stbtt_GetCodepointHMetrics(&f.info, codes[i], &advance, &bearing);
    x += advance * scale;
    if (i + 1 < codes.size()) x += scale * stbtt_GetCodepointKernAdvance(&f.info, codes[i], codes[i + 1]);
  }
  m.width = x;
  return m;
}

double draw_text(Image& image, double x, double y, const std::string& text, double size_px, const Vec4f& colour,
                 TextAlign align) {
  if (!(size_px > 0) || size_px > 2000 || text.empty()) return 0.0;
  if (!(std::abs(x) < 1e6) || !(std::abs(y) < 1e6)) return 0.0;  // far off the picture (or NaN)
  const Font& f = font();
  const TextMetrics metrics = measure_text(text, size_px);
  if (align == TextAlign::centre) x -= 0.5 * metrics.width;
  if (align == TextAlign::right) x -= metrics.width;
  const float scale = stbtt_ScaleForMappingEmToPixels(&f.info, static_cast<float>(size_px));
  const double baseline = y + metrics.ascent;
  const std::vector<int> codes = decode_utf8(text);
  double pen = x;
  std::vector<unsigned char> bitmap;
  for (std::size_t i = 0; i < codes.size(); ++i) {
    const double origin_x = std::floor(pen), origin_y = std::floor(baseline);
    const float shift_x = static_cast<float>(pen - origin_x), shift_y = static_cast<float>(baseline - origin_y);
    int x0, y0, x1, y1;
    stbtt_GetCodepointBitmapBoxSubpixel(&f.info, codes[i], scale, scale, shift_x, shift_y, &x0, &y0, &x1, &y1);
    const int w = x1 - x0, h = y1 - y0;
    if (w > 0 && h > 0) {
      bitmap.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
      stbtt_MakeCodepointBitmapSubpixel(&f.info, bitmap.data(), w, h, w, scale, scale, shift_x, shift_y, codes[i]);
      const int bx = static_cast<int>(origin_x) + x0, by = static_cast<int>(origin_y) + y0;
      for (int j = 0; j < h; ++j)
        for (int k = 0; k < w; ++k) {
          const unsigned char c =
              bitmap[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(k)];
          if (c) blend_pixel(image, bx + k, by + j, colour, static_cast<float>(c) / 255.0f);
        }
    }
    int advance, bearing;
    stbtt_GetCodepointHMetrics(&f.info, codes[i], &advance, &bearing);
    pen += advance * scale;
    if (i + 1 < codes.size()) pen += scale * stbtt_GetCodepointKernAdvance(&f.info, codes[i], codes[i + 1]);
  }
  return metrics.width;
}

double draw_text_with_halo(Image& image, double x, double y, const std::string& text, double size_px,
                           const Vec4f& colour, const Vec4f& halo, double halo_px, TextAlign align) {
  const double r = std::isfinite(halo_px) ? std::clamp(halo_px, 0.0, 20.0) : 0.0;
  if (r > 0) {
    Vec4f soft = halo;
    soft[3] *= 0.6f;  // eight overlapping copies: keep the halo from turning into a solid box
    for (int k = 0; k < 8; ++k) {
      const double a = k * 0.25 * 3.14159265358979323846;
      draw_text(image, x + r * std::cos(a), y + r * std::sin(a), text, size_px, soft, align);
    }
  }
  return draw_text(image, x, y, text, size_px, colour, align);
}

}  // namespace forensim
