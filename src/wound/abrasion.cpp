#include "wound/abrasion.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/image_ops.hpp"
#include "texture/shape_erosion.hpp"
#include "texture/value_noise.hpp"

namespace forensim {

namespace {

using namespace abrasion_colors;

// One noise layer with the thesis's octaves, persistence, bias and gain over the wound's box (noise is only
// read inside the wound), its periods raised to keep the look in mm at the canvas's density; `salt` makes
// the layers independent.
Image thesis_noise(const WoundCanvas& c, const AbrasionParams& p, int octaves, double persistence, double bias,
                   double gain, std::uint64_t salt) {
  ValueNoiseParams n;
  n.octaves = octaves;
  n.persistence = persistence;
  n.bias = bias;
  n.gain = gain;
  n.first_octave = std::max(0, static_cast<int>(std::lround(std::log2(c.texels_per_mm / p.thesis_texels_per_mm))));
  n.seed = mix64(c.seed ^ mix64(salt));
  return value_noise(std::max(c.wound_box.width(), 1), std::max(c.wound_box.height(), 1), n);
}

// Row pointers of the canvas and the output maps (all RGBA inputs have 4 channels, see make_wound_canvas).
struct Row {
  const float* upper;
  const float* lower;
  const float* shape;
  const float* outside;
  const float* inside;
  float* color;
  float* reflection;
  float* height;
};

Row row(const WoundCanvas& c, MapSet& m, int y) {
  return {c.upper_skin.pixel(0, y), c.lower_skin.pixel(0, y), c.shape.pixel(0, y),      c.outside_mm.pixel(0, y),
          c.inside_mm.pixel(0, y),  m.color.pixel(0, y),      m.reflection.pixel(0, y), m.height_mm.pixel(0, y)};
}

inline void store(float* out, const Vec4f& v) {
  out[0] = v[0];
  out[1] = v[1];
  out[2] = v[2];
  out[3] = v[3];
}

inline Vec4f load(const float* p) {
  return Vec4f(p[0], p[1], p[2], p[3]);
}

Vec4f lerp4(const Vec4f& a, const Vec4f& b, float t) {
  return a + (b - a) * t;
}

Vec4f mul4(const Vec4f& a, const Vec4f& b) {
  return a.cwiseProduct(b);
}

// The red glow outside the wound (chapter 4.3.2): Lerp(WOUND_RED, upper skin, d / thickness), upper skin beyond.
inline void glow(const Row& r, int x, float thickness_mm) {
  const float* up = r.upper + 4 * x;
  const float d = r.outside[x];
  if (!(d <= thickness_mm)) {
    std::copy_n(up, 4, r.color + 4 * x);
    return;
  }
  store(r.color + 4 * x, lerp4(wound_red, load(up), d / thickness_mm));
}

bool inside(const WoundCanvas& c, int x, int y) {
  return c.shape.at(x, y) >= 0.5f;
}

void check_canvas(const WoundCanvas& c) {
  if (c.upper_skin.channels() != 4 || c.lower_skin.channels() != 4 || c.upper_skin.width() != c.width() ||
      c.lower_skin.width() != c.width() || c.shape.width() != c.width() || c.outside_mm.width() != c.width() ||
      c.inside_mm.width() != c.width() || c.upper_skin.height() != c.height() || c.shape.height() != c.height()) {
    throw InputError("wound canvas", "maps", "skin maps must be RGBA and all maps of the region's size");
  }
}

template <typename F>
void for_rows(int height, F&& f) {
  parallel_for(
      0, static_cast<std::size_t>(height), [&](std::size_t y) { f(static_cast<int>(y)); }, 4);
}

// Erosion range of m in thesis texels, at the canvas's density.
std::pair<int, int> erosion_range(const WoundCanvas& c, const AbrasionParams& p, int m_min, int m_max) {
  const double k = c.texels_per_mm / p.thesis_texels_per_mm;
  const int lo = std::clamp(static_cast<int>(std::lround(m_min * k)), 1, 4096);
  const int hi = std::clamp(static_cast<int>(std::lround(m_max * k)), lo, 4096);
  return {lo, hi};
}

// Eq. 4.8's maxOuterGradBorder. Never below the deepest inside distance, so the wound closes at position 1
// whatever the discrete border gives for the diameter.
double max_outer_border_mm(const WoundCanvas& c, const AbrasionParams& p) {
  double deepest = 0.0;
  for (float v : c.inside_mm.data()) deepest = std::max(deepest, static_cast<double>(v));
  return p.thesis_closing_distance ? std::max(c.closing_distance_mm * 0.5, deepest) : deepest;
}

}  // namespace

double AbrasionParams::reach_mm() const {
  return px_to_mm(std::max(glow_thickness_px, scab_gradient_px)) + 0.5;
}

void VasoconstrictionKey::render_into(const WoundCanvas& c, double, MapSet& m) const {
  check_canvas(c);
  prepare_map_set(m, c.width(), c.height(), m_params.skin_reflection);
  for_rows(c.height(), [&](int y) {
    const Row r = row(c, m, y);
    for (int x = 0; x < c.width(); ++x)
      std::copy_n((r.shape[x] >= 0.5f ? r.lower : r.upper) + 4 * x, 4, r.color + 4 * x);
  });
}

void VasodilationKey::render_into(const WoundCanvas& c, double, MapSet& m) const {
  check_canvas(c);
  const AbrasionParams& p = m_params;
  prepare_map_set(m, c.width(), c.height(), p.skin_reflection);
  const auto [a0, a1] = erosion_range(c, p, 3, 5);
  const auto [b0, b1] = erosion_range(c, p, 3, 10);
  // Erode the shape over its box plus a margin wider than the kernels, so the outside stays in view.
  const TexelRect& box = c.wound_box;
  const int margin = b1 + 2;
  const int ex0 = std::max(box.x0 - margin, 0), ex1 = std::min(box.x1 + margin, c.width());
  const Image shape_crop = c.shape.crop(ex0, box.y0, ex1 - ex0, box.height());
  const Image eroded = erode_shape(erode_shape(shape_crop, a0, a1, mix64(c.seed ^ 0xE1)), b0, b1, mix64(c.seed ^ 0xE2));
  const Image scrape = thesis_noise(c, p, 5, 0.09, 0.5, 0.43, 0x5C);
  const float glow_mm = static_cast<float>(p.px_to_mm(p.glow_thickness_px));
  for_rows(c.height(), [&](int y) {
    const Row r = row(c, m, y);
    for (int x = 0; x < c.width(); ++x) {
      if (r.shape[x] < 0.5f) {
        glow(r, x, glow_mm);
      } else if (eroded.at(x - ex0, y - box.y0) >= 0.5f) {
        store(r.color + 4 * x, mul4(load(r.lower + 4 * x), wound_red));
        // Scrape marks: the noise stretched 6400% along y (chapter 4.3.2, Figure 4.6).
        r.reflection[x] = sample_bilinear(scrape, x - box.x0 + 0.5, (y - box.y0 + 0.5) / 64.0, 0, WrapMode::wrap);
      } else {
        store(r.color + 4 * x, mul4(load(r.upper + 4 * x), edge_grey));
      }
    }
  });
}

void ScabFormingKey::render_into(const WoundCanvas& c, double, MapSet& m) const {
  check_canvas(c);
  const AbrasionParams& p = m_params;
  prepare_map_set(m, c.width(), c.height(), p.skin_reflection);
  const Image bottom = thesis_noise(c, p, 5, 0.85, 0.54, 0.21, 0xB0);
  const Image speckle = thesis_noise(c, p, 5, 0.48, 0.16, 0.15, 0x5E);
  const float glow_mm = static_cast<float>(p.px_to_mm(p.glow_thickness_px));
  const TexelRect& box = c.wound_box;
  for_rows(c.height(), [&](int y) {
    const Row r = row(c, m, y);
    for (int x = 0; x < c.width(); ++x) {
      if (r.shape[x] < 0.5f) {
        glow(r, x, glow_mm);
        continue;
      }
      const float nb = bottom.at(x - box.x0, y - box.y0);
      // Eq. 4.5: lowerWoundColor = lowerSkin * noise.r + upperSkin * (1 - noise.r).
      const Vec4f lower_wound = load(r.lower + 4 * x) * nb + load(r.upper + 4 * x) * (1.0f - nb);
      // Eq. 4.6 with speckleWoundColor = speckle noise x (0.88, 0.20, 0.22).
      const Vec4f sp = speckle_red * speckle.at(x - box.x0, y - box.y0);
      Vec4f out = sp * sp.x() + lower_wound * (1.0f - sp.x());
      out.w() = 1.0f;
      store(r.color + 4 * x, out);
    }
  });
}

void ScabKey::render_into(const WoundCanvas& c, double, MapSet& m) const {
  check_canvas(c);
  const AbrasionParams& p = m_params;
  prepare_map_set(m, c.width(), c.height(), p.skin_reflection);
  const Image mask = thesis_noise(c, p, 7, 1.0, 0.44, 0.02, 0x4A);
  const Image body = thesis_noise(c, p, 5, 0.54, 0.3, 0.69, 0x4B);
  const Image rim_noise = thesis_noise(c, p, 5, 0.33, 0.60, 0.59, 0x4C);
  const Image shine = thesis_noise(c, p, 10, 1.0, 0.25, 0.95, 0x4D);
  const float glow_mm = static_cast<float>(p.px_to_mm(p.glow_thickness_px));
  const float rim_mm = static_cast<float>(p.px_to_mm(p.scab_gradient_px));
  const float height_mm = static_cast<float>(p.scab_height_mm);
  const TexelRect& box = c.wound_box;
  const Vec4f white(1, 1, 1, 1), black(0, 0, 0, 1);
  for_rows(c.height(), [&](int y) {
    const Row r = row(c, m, y);
    for (int x = 0; x < c.width(); ++x) {
      if (r.shape[x] < 0.5f) {
        glow(r, x, glow_mm);
        continue;
      }
      const int bx = x - box.x0, by = y - box.y0;
      const float h = mask.at(bx, by) * body.at(bx, by);  // Figure 4.10: masked noise
      r.height[x] = h * height_mm;
      const float d = r.inside[x];
      Vec4f rim = d <= rim_mm ? lerp4(scab_rim_red, black, d / rim_mm) : black;
      rim *= rim_noise.at(bx, by);
      const Vec4f inner = lerp4(scab_light, scab_dark, h);
      // Eq. 4.7: finalColor = innerColor + gradientColor * (white - innerColor).
      Vec4f out = inner + mul4(rim, white - inner);
      out.w() = 1.0f;
      store(r.color + 4 * x, out);
      r.reflection[x] = shine.at(bx, by);
    }
  });
}

std::pair<double, double> MaturationKey::borders_mm(const WoundCanvas& c, double position) const {
  const double max_outer = max_outer_border_mm(c, m_params);
  const double shrink =
      m_params.shrink_min + (m_params.shrink_max - m_params.shrink_min) * hash_uniform(c.seed, 0x4D41);
  const double outer = max_outer * std::clamp(position, 0.0, 1.0);
  return {outer, outer + max_outer * shrink};
}

void MaturationKey::render_into(const WoundCanvas& c, double position, MapSet& m) const {
  check_canvas(c);
  const AbrasionParams& p = m_params;
  prepare_map_set(m, c.width(), c.height(), p.skin_reflection);
  const auto [outer, inner] = borders_mm(c, position);
  const double half = max_outer_border_mm(c, p);
  const float fo = static_cast<float>(outer), fi = static_cast<float>(inner);
  const float inv1 = inner > outer ? static_cast<float>(1.0 / (inner - outer)) : 0.0f;
  const float inv2 = half > inner ? static_cast<float>(1.0 / (half - inner)) : 0.0f;
  for_rows(c.height(), [&](int y) {
    const Row r = row(c, m, y);
    for (int x = 0; x < c.width(); ++x) {
      const float d = r.inside[x];
      if (r.shape[x] < 0.5f || d <= fo) {  // Algorithm 4.4, lines 3 to 5
        std::copy_n(r.upper + 4 * x, 4, r.color + 4 * x);
      } else if (d <= fi) {  // lines 6 to 10
        const float t = inv1 > 0.0f ? (d - fo) * inv1 : 1.0f;
        store(r.color + 4 * x, lerp4(load(r.upper + 4 * x), wound_red, t));
      } else {  // lines 11 to 15
        const float t = inv2 > 0.0f ? std::clamp((d - fi) * inv2, 0.0f, 1.0f) : 1.0f;
        store(r.color + 4 * x, lerp4(wound_red, wound_white, t));
      }
    }
  });
}

std::shared_ptr<const KeyPosition> make_abrasion_key(const std::string& phase, const AbrasionParams& params) {
  if (phase == "vasoconstriction") return std::make_shared<VasoconstrictionKey>(params);
  if (phase == "vasodilation") return std::make_shared<VasodilationKey>(params);
  if (phase == "scab_forming") return std::make_shared<ScabFormingKey>(params);
  if (phase == "scab") return std::make_shared<ScabKey>(params);
  if (phase == "maturation") return std::make_shared<MaturationKey>(params);
  throw InputError("abrasion", "phase '" + phase + "'",
                   "unknown phase (vasoconstriction, vasodilation, scab_forming, scab, maturation)");
}

std::vector<TimelineEntry> default_abrasion_timeline(const AbrasionParams& params) {
  const double minute = 60.0, hour = 3600.0, day = 86400.0;
  const auto vc = make_abrasion_key("vasoconstriction", params);
  const auto vd = make_abrasion_key("vasodilation", params);
  const auto sf = make_abrasion_key("scab_forming", params);
  const auto sc = make_abrasion_key("scab", params);
  const auto mt = make_abrasion_key("maturation", params);
  return {
      {0.0, vc, 0.0, "vasoconstriction"},        {5 * minute, vc, 0.0, "vasoconstriction (held)"},
      {15 * minute, vd, 0.0, "vasodilation"},    {2 * hour, sf, 0.0, "scab-forming"},
      {2 * day, sf, 0.0, "scab-forming (held)"}, {5 * day, sc, 0.0, "scab"},
      {10 * day, sc, 0.0, "scab (held)"},        {10 * day, mt, 0.0, "maturation start"},
      {28 * day, mt, 1.0, "maturation end"},
  };
}

std::size_t visible_wound_texels(const WoundCanvas& c, const MapSet& maps, float tolerance) {
  std::size_t n = 0;
  for (int y = 0; y < c.height(); ++y) {
    for (int x = 0; x < c.width(); ++x) {
      if (!inside(c, x, y)) continue;
      const Vec4f d = maps.color.rgba(x, y) - c.upper_skin.rgba(x, y);
      if (d.head<3>().cwiseAbs().maxCoeff() > tolerance) ++n;
    }
  }
  return n;
}

}  // namespace forensim
