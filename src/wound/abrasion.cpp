#include "wound/abrasion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

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
// the layers independent. Evaluated per tile where the wound is.
ValueNoiseField thesis_noise(const WoundCanvas& c, const AbrasionParams& p, int octaves, double persistence,
                             double bias, double gain, std::uint64_t salt) {
  ValueNoiseParams n;
  n.octaves = octaves;
  n.persistence = persistence;
  n.bias = bias;
  n.gain = gain;
  n.first_octave = std::max(0, static_cast<int>(std::lround(std::log2(c.texels_per_mm / p.thesis_texels_per_mm))));
  n.seed = mix64(c.seed ^ mix64(salt));
  return ValueNoiseField(std::max(c.wound_box.width(), 1), std::max(c.wound_box.height(), 1), n);
}

// Noise of a layer over the inside texels' box `ib` of the tile whose rect is `r` (texel (x, y) at
// (y - r.y0) * tile + x - r.x0; other texels are left unset). `slot` picks one of a thread's buffers.
const float* noise_tile(const ValueNoiseField& f, const WoundCanvas& c, const TexelRect& r, const TexelRect& ib,
                        int slot) {
  thread_local std::array<std::vector<float>, 4> buffers;
  auto& b = buffers[static_cast<std::size_t>(slot)];
  b.resize(tiled_map_tile_texels);
  f.evaluate(
      ib.x0 - c.wound_box.x0, ib.y0 - c.wound_box.y0, ib.width(), ib.height(),
      b.data() + static_cast<std::size_t>(ib.y0 - r.y0) * tiled_map_tile + static_cast<std::size_t>(ib.x0 - r.x0),
      tiled_map_tile);
  return b.data();
}

// Row pointers of the canvas (all RGBA inputs have 4 channels, see make_wound_canvas).
struct Row {
  const float* upper;
  const float* lower;
  const float* shape;
  const float* outside;
  const float* inside;
};

Row row(const WoundCanvas& c, int y) {
  return {c.upper_skin.pixel(0, y), c.lower_skin.pixel(0, y), c.shape.pixel(0, y), c.outside_mm.pixel(0, y),
          c.inside_mm.pixel(0, y)};
}

inline void put(std::uint16_t* out, std::size_t i, const Vec4f& v) {
  to_unorm16x4(v.data(), out + 4 * i);
}

inline void put(std::uint16_t* out, std::size_t i, const float* v) {
  to_unorm16x4(v, out + 4 * i);
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
inline void glow(std::uint16_t* color, std::size_t i, const Row& r, int x, float thickness_mm) {
  const float* up = r.upper + 4 * x;
  const float d = r.outside[x];
  if (!(d <= thickness_mm)) {
    put(color, i, up);
    return;
  }
  put(color, i, lerp4(wound_red, load(up), d / thickness_mm));
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

// A tile to render and the storage of the maps it writes (null: that map stays the skin there). A job writes
// every texel of its rect in each map it has.
struct TileJob {
  int tile = 0;
  TexelRect rect;
  const CanvasTile* info = nullptr;
  std::uint16_t* color = nullptr;
  std::uint16_t* reflection = nullptr;
  float* height = nullptr;
  // Index of region texel (x, y) in the tile's storage.
  std::size_t at(int x, int y) const {
    return static_cast<std::size_t>(y - rect.y0) * tiled_map_tile + static_cast<std::size_t>(x - rect.x0);
  }
};

struct Wants {
  bool color = false, reflection = false, height = false;
};

// Resets `m` to the skin, takes storage for the maps `want(tile info)` asks for (serially), then runs
// body(job) over those tiles in parallel (one tile per task: the same maps at any thread count).
template <typename Want, typename Body>
void render_tiles(const WoundCanvas& c, TiledMapSet& m, float skin_reflection, Want&& want, Body&& body) {
  m.reset(c.width(), c.height(), skin_reflection);
  std::vector<CanvasTile> scratch;
  const auto& tiles = canvas_tiles(c, scratch);
  std::vector<TileJob> jobs;
  for (int t = 0; t < m.tile_count(); ++t) {
    const CanvasTile& info = tiles[static_cast<std::size_t>(t)];
    const Wants w = want(info);
    if (!w.color && !w.reflection && !w.height) continue;
    TileJob job;
    job.tile = t;
    job.rect = m.tile_rect(t);
    job.info = &info;
    if (w.color) job.color = m.own_color(t);
    if (w.reflection) job.reflection = m.own_reflection(t);
    if (w.height) job.height = m.own_height(t);
    jobs.push_back(job);
  }
  parallel_for(
      0, jobs.size(), [&](std::size_t i) { body(jobs[i]); }, 1);
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
  std::vector<CanvasTile> scratch;
  float deepest = 0.0f;
  for (const auto& t : canvas_tiles(c, scratch)) deepest = std::max(deepest, t.max_inside_mm);
  return p.thesis_closing_distance ? std::max(c.closing_distance_mm * 0.5, static_cast<double>(deepest))
                                   : static_cast<double>(deepest);
}

int wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

}  // namespace

double AbrasionParams::reach_mm() const {
  return px_to_mm(std::max(glow_thickness_px, scab_gradient_px)) + 0.5;
}

void VasoconstrictionKey::render_into(const WoundCanvas& c, double, TiledMapSet& m) const {
  check_canvas(c);
  render_tiles(
      c, m, m_params.skin_reflection,
      [](const CanvasTile& t) {
        return Wants{t.inside > 0, false, false};
      },
      [&](const TileJob& job) {
        for (int y = job.rect.y0; y < job.rect.y1; ++y) {
          const Row r = row(c, y);
          for (int x = job.rect.x0; x < job.rect.x1; ++x)
            put(job.color, job.at(x, y), (r.shape[x] >= 0.5f ? r.lower : r.upper) + 4 * x);
        }
      });
}

void VasodilationKey::render_into(const WoundCanvas& c, double, TiledMapSet& m) const {
  check_canvas(c);
  const AbrasionParams& p = m_params;
  const auto [a0, a1] = erosion_range(c, p, 3, 5);
  const auto [b0, b1] = erosion_range(c, p, 3, 10);
  // Algorithm 3.1 twice along rows over the shape's box plus a margin wider than the kernels (so the outside
  // stays in view), widths drawn per texel of that crop; computed per tile row, over the tile's columns
  // widened by both kernels' half-widths, which gives the crop's values there exactly.
  const TexelRect& box = c.wound_box;
  const int margin = b1 + 2;
  const int ex0 = std::max(box.x0 - margin, 0), ex1 = std::min(box.x1 + margin, c.width());
  const std::uint64_t crop_width = static_cast<std::uint64_t>(ex1 - ex0);
  const std::uint64_t seed1 = mix64(c.seed ^ 0xE1), seed2 = mix64(c.seed ^ 0xE2);
  const int reach = erosion_kernel_width(a1) / 2 + erosion_kernel_width(b1) / 2;
  // Eroded mask of row y over [x0, x1) into out[x - x0] (only the columns of the crop, where the wound is).
  auto eroded_row = [&](int y, int x0, int x1, float* out) {
    thread_local std::vector<float> in, once, twice;
    const int cx0 = std::max(x0, ex0), cx1 = std::min(x1, ex1);
    if (cx1 <= cx0) return;
    const int s0 = std::max(ex0, cx0 - reach), s1 = std::min(ex1, cx1 + reach);
    const std::size_t n = static_cast<std::size_t>(s1 - s0);
    in.resize(n);
    once.resize(n);
    twice.resize(n);
    const float* shape = c.shape.pixel(0, y);
    for (std::size_t i = 0; i < n; ++i) in[i] = shape[static_cast<std::size_t>(s0) + i] >= 0.5f ? 1.0f : 0.0f;
    const std::uint64_t index0 =
        static_cast<std::uint64_t>(y - box.y0) * crop_width + static_cast<std::uint64_t>(s0 - ex0);
    erode_binary_line(in.data(), 1, static_cast<int>(n), a0, a1, seed1, index0, 1, once.data(), 1);
    erode_binary_line(once.data(), 1, static_cast<int>(n), b0, b1, seed2, index0, 1, twice.data(), 1);
    std::copy_n(twice.data() + (cx0 - s0), cx1 - cx0, out + (cx0 - x0));
  };
  // Scrape marks: the noise stretched 6400% along y (chapter 4.3.2, Figure 4.6), sampled bilinearly with
  // wrap-around at (x + 0.5, (y + 0.5) / 64): only the noise rows those samples read are evaluated.
  const ValueNoiseField scrape = thesis_noise(c, p, 5, 0.09, 0.5, 0.43, 0x5C);
  const int bw = scrape.width(), bh = scrape.height();
  struct RowTaps {
    int a, b;
    float t;
  };
  std::vector<RowTaps> taps(static_cast<std::size_t>(bh));
  std::vector<int> rows;
  for (int y = 0; y < bh; ++y) {
    const double fy = (y + 0.5) / 64.0 - 0.5;
    const double y0f = std::floor(fy);
    const int y0 = static_cast<int>(y0f);
    taps[static_cast<std::size_t>(y)] = {wrap(y0, bh), wrap(y0 + 1, bh), static_cast<float>(fy - y0f)};
    rows.push_back(wrap(y0, bh));
    rows.push_back(wrap(y0 + 1, bh));
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  std::vector<float> scrape_rows(rows.size() * static_cast<std::size_t>(bw));
  parallel_for(
      0, rows.size(),
      [&](std::size_t i) {
        scrape.evaluate(0, rows[i], bw, 1, scrape_rows.data() + i * static_cast<std::size_t>(bw), 0);
      },
      1);
  // Taps as offsets of their rows in scrape_rows.
  auto offset_of = [&](int r) {
    return static_cast<int>(std::lower_bound(rows.begin(), rows.end(), r) - rows.begin()) * bw;
  };
  for (auto& t : taps) {
    t.a = offset_of(t.a);
    t.b = offset_of(t.b);
  }
  const float glow_mm = static_cast<float>(p.px_to_mm(p.glow_thickness_px));
  const std::uint16_t skin_reflection = to_unorm16(p.skin_reflection);
  render_tiles(
      c, m, p.skin_reflection,
      [&](const CanvasTile& t) {
        return Wants{t.inside > 0 || t.min_outside_mm <= glow_mm, t.inside > 0, false};
      },
      [&](const TileJob& job) {
        float eroded[tiled_map_tile];
        const TexelRect& ib = job.info->inside_box;
        for (int y = job.rect.y0; y < job.rect.y1; ++y) {
          const Row r = row(c, y);
          if (y >= ib.y0 && y < ib.y1) eroded_row(y, job.rect.x0, job.rect.x1, eroded);
          for (int x = job.rect.x0; x < job.rect.x1; ++x) {
            const std::size_t i = job.at(x, y);
            if (job.reflection) job.reflection[i] = skin_reflection;
            if (r.shape[x] < 0.5f) {
              glow(job.color, i, r, x, glow_mm);
            } else if (eroded[x - job.rect.x0] >= 0.5f) {
              put(job.color, i, mul4(load(r.lower + 4 * x), wound_red));
              const RowTaps& t = taps[static_cast<std::size_t>(y - box.y0)];
              const float top = scrape_rows[static_cast<std::size_t>(t.a + x - box.x0)];
              const float bottom = scrape_rows[static_cast<std::size_t>(t.b + x - box.x0)];
              job.reflection[i] = to_unorm16(top * (1 - t.t) + bottom * t.t);
            } else {
              put(job.color, i, mul4(load(r.upper + 4 * x), edge_grey));
            }
          }
        }
      });
}

void ScabFormingKey::render_into(const WoundCanvas& c, double, TiledMapSet& m) const {
  check_canvas(c);
  const AbrasionParams& p = m_params;
  const ValueNoiseField bottom = thesis_noise(c, p, 5, 0.85, 0.54, 0.21, 0xB0);
  const ValueNoiseField speckle = thesis_noise(c, p, 5, 0.48, 0.16, 0.15, 0x5E);
  const float glow_mm = static_cast<float>(p.px_to_mm(p.glow_thickness_px));
  render_tiles(
      c, m, p.skin_reflection,
      [&](const CanvasTile& t) {
        return Wants{t.inside > 0 || t.min_outside_mm <= glow_mm, false, false};
      },
      [&](const TileJob& job) {
        const bool wound = job.info->inside > 0;
        const float* nb = wound ? noise_tile(bottom, c, job.rect, job.info->inside_box, 0) : nullptr;
        const float* ns = wound ? noise_tile(speckle, c, job.rect, job.info->inside_box, 1) : nullptr;
        for (int y = job.rect.y0; y < job.rect.y1; ++y) {
          const Row r = row(c, y);
          for (int x = job.rect.x0; x < job.rect.x1; ++x) {
            const std::size_t i = job.at(x, y);
            if (r.shape[x] < 0.5f) {
              glow(job.color, i, r, x, glow_mm);
              continue;
            }
            // Eq. 4.5: lowerWoundColor = lowerSkin * noise.r + upperSkin * (1 - noise.r).
            const Vec4f lower_wound = load(r.lower + 4 * x) * nb[i] + load(r.upper + 4 * x) * (1.0f - nb[i]);
            // Eq. 4.6 with speckleWoundColor = speckle noise x (0.88, 0.20, 0.22).
            const Vec4f sp = speckle_red * ns[i];
            Vec4f out = sp * sp.x() + lower_wound * (1.0f - sp.x());
            out.w() = 1.0f;
            put(job.color, i, out);
          }
        }
      });
}

void ScabKey::render_into(const WoundCanvas& c, double, TiledMapSet& m) const {
  check_canvas(c);
  const AbrasionParams& p = m_params;
  const ValueNoiseField mask = thesis_noise(c, p, 7, 1.0, 0.44, 0.02, 0x4A);
  const ValueNoiseField body = thesis_noise(c, p, 5, 0.54, 0.3, 0.69, 0x4B);
  const ValueNoiseField rim_noise = thesis_noise(c, p, 5, 0.33, 0.60, 0.59, 0x4C);
  const ValueNoiseField shine = thesis_noise(c, p, 10, 1.0, 0.25, 0.95, 0x4D);
  const float glow_mm = static_cast<float>(p.px_to_mm(p.glow_thickness_px));
  const float rim_mm = static_cast<float>(p.px_to_mm(p.scab_gradient_px));
  const float height_mm = static_cast<float>(p.scab_height_mm);
  const std::uint16_t skin_reflection = to_unorm16(p.skin_reflection);
  const Vec4f white(1, 1, 1, 1), black(0, 0, 0, 1);
  render_tiles(
      c, m, p.skin_reflection,
      [&](const CanvasTile& t) {
        return Wants{t.inside > 0 || t.min_outside_mm <= glow_mm, t.inside > 0, t.inside > 0};
      },
      [&](const TileJob& job) {
        const bool wound = job.info->inside > 0;
        const float* nm = wound ? noise_tile(mask, c, job.rect, job.info->inside_box, 0) : nullptr;
        const float* nb = wound ? noise_tile(body, c, job.rect, job.info->inside_box, 1) : nullptr;
        const float* nr = wound ? noise_tile(rim_noise, c, job.rect, job.info->inside_box, 2) : nullptr;
        const float* ns = wound ? noise_tile(shine, c, job.rect, job.info->inside_box, 3) : nullptr;
        for (int y = job.rect.y0; y < job.rect.y1; ++y) {
          const Row r = row(c, y);
          for (int x = job.rect.x0; x < job.rect.x1; ++x) {
            const std::size_t i = job.at(x, y);
            if (r.shape[x] < 0.5f) {
              glow(job.color, i, r, x, glow_mm);
              if (job.reflection) job.reflection[i] = skin_reflection;
              if (job.height) job.height[i] = 0.0f;
              continue;
            }
            const float h = nm[i] * nb[i];  // Figure 4.10: masked noise
            job.height[i] = h * height_mm;
            const float d = r.inside[x];
            Vec4f rim = d <= rim_mm ? lerp4(scab_rim_red, black, d / rim_mm) : black;
            rim *= nr[i];
            const Vec4f inner = lerp4(scab_light, scab_dark, h);
            // Eq. 4.7: finalColor = innerColor + gradientColor * (white - innerColor).
            Vec4f out = inner + mul4(rim, white - inner);
            out.w() = 1.0f;
            put(job.color, i, out);
            job.reflection[i] = to_unorm16(ns[i]);
          }
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

void MaturationKey::render_into(const WoundCanvas& c, double position, TiledMapSet& m) const {
  check_canvas(c);
  const AbrasionParams& p = m_params;
  const auto [outer, inner] = borders_mm(c, position);
  const double half = max_outer_border_mm(c, p);
  const float fo = static_cast<float>(outer), fi = static_cast<float>(inner);
  const float inv1 = inner > outer ? static_cast<float>(1.0 / (inner - outer)) : 0.0f;
  const float inv2 = half > inner ? static_cast<float>(1.0 / (half - inner)) : 0.0f;
  render_tiles(
      c, m, p.skin_reflection,
      // Only texels inside the wound deeper than the outer border differ from the skin.
      [&](const CanvasTile& t) {
        return Wants{t.inside > 0 && t.max_inside_mm > fo, false, false};
      },
      [&](const TileJob& job) {
        for (int y = job.rect.y0; y < job.rect.y1; ++y) {
          const Row r = row(c, y);
          for (int x = job.rect.x0; x < job.rect.x1; ++x) {
            const std::size_t i = job.at(x, y);
            const float d = r.inside[x];
            if (r.shape[x] < 0.5f || d <= fo) {  // Algorithm 4.4, lines 3 to 5
              put(job.color, i, r.upper + 4 * x);
            } else if (d <= fi) {  // lines 6 to 10
              const float t = inv1 > 0.0f ? (d - fo) * inv1 : 1.0f;
              put(job.color, i, lerp4(load(r.upper + 4 * x), wound_red, t));
            } else {  // lines 11 to 15
              const float t = inv2 > 0.0f ? std::clamp((d - fi) * inv2, 0.0f, 1.0f) : 1.0f;
              put(job.color, i, lerp4(wound_red, wound_white, t));
            }
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
