#include "wound/map_set.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "image/exr_io.hpp"
#include "image/png_io.hpp"
#include "texture/normal_from_height.hpp"

namespace forensim {

MapSet make_map_set(int width, int height, const Vec4f& color, float reflection) {
  MapSet set;
  set.color = Image(width, height, 4, 0.0f, PixelEncoding::linear);
  set.color.fill(color);
  set.reflection = Image(width, height, 1, reflection, PixelEncoding::data);
  set.height_mm = Image(width, height, 1, 0.0f, PixelEncoding::data);
  return set;
}

void prepare_map_set(MapSet& set, int width, int height, float reflection) {
  if (set.color.width() != width || set.color.height() != height || set.color.channels() != 4 ||
      set.reflection.width() != width || set.reflection.height() != height || set.reflection.channels() != 1 ||
      set.height_mm.width() != width || set.height_mm.height() != height || set.height_mm.channels() != 1) {
    set = make_map_set(width, height, Vec4f(0, 0, 0, 1), reflection);
    return;
  }
  set.color.set_encoding(PixelEncoding::linear);
  float* r = set.reflection.data().data();
  float* h = set.height_mm.data().data();
  parallel_for_chunks(
      0, set.reflection.data().size(),
      [&](std::size_t begin, std::size_t end) {
        std::fill(r + begin, r + end, reflection);
        std::fill(h + begin, h + end, 0.0f);
      },
      1 << 16);
}

void check_map_set(const MapSet& set, const std::string& what) {
  const int w = set.color.width();
  const int h = set.color.height();
  if (set.color.channels() != 4 || set.reflection.channels() != 1 || set.height_mm.channels() != 1) {
    throw InputError(what, "maps", "expected RGBA colour and 1-channel reflection and height");
  }
  if (set.reflection.width() != w || set.reflection.height() != h || set.height_mm.width() != w ||
      set.height_mm.height() != h) {
    throw InputError(what, "maps", "colour, reflection and height differ in size");
  }
}

namespace {

bool same_shape(const MapSet& a, const MapSet& b) {
  return a.width() == b.width() && a.height() == b.height() && a.color.channels() == b.color.channels() &&
         a.reflection.width() == b.reflection.width() && a.height_mm.width() == b.height_mm.width() &&
         a.reflection.height() == b.reflection.height() && a.height_mm.height() == b.height_mm.height();
}

// out[i] = a[i] + (b[i] - a[i]) t over n floats (vectorises; out may alias a or b).
inline void lerp_span(const float* a, const float* b, float* out, std::size_t n, float t) {
  const float s = 1.0f - t;
  for (std::size_t i = 0; i < n; ++i) out[i] = a[i] * s + b[i] * t;
}

}  // namespace

void lerp_map_sets(const MapSet& a, const MapSet& b, float t, MapSet& out, const TexelRect& rect) {
  check_map_set(a, "lerp_map_sets a");
  if (!same_shape(a, b) || !same_shape(a, out)) {
    throw InputError("lerp_map_sets", "maps", "the sets differ in size or channels");
  }
  const TexelRect r{std::max(rect.x0, 0), std::max(rect.y0, 0), std::min(rect.x1, a.width()),
                    std::min(rect.y1, a.height())};
  if (r.empty()) return;
  const std::size_t w = static_cast<std::size_t>(a.width());
  const std::size_t x0 = static_cast<std::size_t>(r.x0);
  const std::size_t n = static_cast<std::size_t>(r.width());
  const float* ac = a.color.data().data();
  const float* bc = b.color.data().data();
  float* oc = out.color.data().data();
  const float* ar = a.reflection.data().data();
  const float* br = b.reflection.data().data();
  float* orf = out.reflection.data().data();
  const float* ah = a.height_mm.data().data();
  const float* bh = b.height_mm.data().data();
  float* oh = out.height_mm.data().data();
  parallel_for_chunks(
      static_cast<std::size_t>(r.y0), static_cast<std::size_t>(r.y1),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t y = begin; y < end; ++y) {
          const std::size_t o = y * w + x0;
          lerp_span(ac + 4 * o, bc + 4 * o, oc + 4 * o, 4 * n, t);
          lerp_span(ar + o, br + o, orf + o, n, t);
          lerp_span(ah + o, bh + o, oh + o, n, t);
        }
      },
      64);
}

void lerp_map_sets(const MapSet& a, const MapSet& b, float t, MapSet& out) {
  lerp_map_sets(a, b, t, out, TexelRect{0, 0, a.width(), a.height()});
}

void paste_map_set(MapSet& full, const MapSet& part, const TexelRect& rect) {
  check_map_set(full, "paste_map_set full");
  check_map_set(part, "paste_map_set part");
  if (part.width() != rect.width() || part.height() != rect.height()) {
    throw InputError("paste_map_set", "rect", "the part's size differs from the rectangle");
  }
  const int x0 = std::max(rect.x0, 0);
  const int x1 = std::min(rect.x1, full.width());
  if (x1 <= x0) return;
  const std::size_t n = static_cast<std::size_t>(x1 - x0);
  const int y0 = std::max(rect.y0, 0);
  const int y1 = std::min(rect.y1, full.height());
  for (int y = y0; y < y1; ++y) {
    const int py = y - rect.y0;
    const int px = x0 - rect.x0;
    std::copy_n(part.color.pixel(px, py), 4 * n, full.color.pixel(x0, y));
    std::copy_n(part.reflection.pixel(px, py), n, full.reflection.pixel(x0, y));
    std::copy_n(part.height_mm.pixel(px, py), n, full.height_mm.pixel(x0, y));
  }
}

Image roughness_from_reflection(const Image& reflection, float min_roughness, float max_roughness) {
  Image out(reflection.width(), reflection.height(), 1, 0.0f, PixelEncoding::data);
  const auto& in = reflection.data();
  auto& o = out.data();
  const int c = reflection.channels();
  for (std::size_t i = 0; i < o.size(); ++i) {
    const float r = std::clamp(in[i * static_cast<std::size_t>(c)], 0.0f, 1.0f);
    o[i] = max_roughness + (min_roughness - max_roughness) * r;
  }
  return out;
}

std::vector<std::string> write_map_set(const MapSet& set, const std::filesystem::path& folder,
                                       const std::string& prefix, double texels_per_mm, double max_height_mm) {
  check_map_set(set, prefix);
  std::vector<std::string> names;
  auto name = [&](const std::string& suffix) {
    names.push_back(prefix + suffix);
    return folder / names.back();
  };
  write_png(name("_color.png"), set.color.with_channels(3));
  write_png(name("_reflection.png"), set.reflection);
  write_png(name("_roughness.png"), roughness_from_reflection(set.reflection));
  write_exr(name("_height.exr"), set.height_mm, ExrPixelType::full_float);
  Image scaled = set.height_mm;
  const float k = max_height_mm > 0.0 ? static_cast<float>(1.0 / max_height_mm) : 1.0f;
  for (float& v : scaled.data()) v *= k;
  write_png(name("_height.png"), scaled);
  write_png(name("_normal.png"), normal_from_height(set.height_mm, texels_per_mm));
  return names;
}

}  // namespace forensim
