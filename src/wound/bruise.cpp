#include "wound/bruise.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/value_noise.hpp"

namespace forensim {

BruiseStage bruise_stage(const std::string& name) {
  if (name == "fresh") return {name, Vec4f(0.62f, 0.22f, 0.30f, 1.0f), 0.75, 1.5, 2.0};
  if (name == "blue") return {name, Vec4f(0.30f, 0.22f, 0.45f, 1.0f), 0.80, 2.5, 3.0};
  if (name == "green") return {name, Vec4f(0.62f, 0.78f, 0.38f, 1.0f), 0.65, 4.0, 4.0};
  if (name == "yellow") return {name, Vec4f(0.95f, 0.82f, 0.42f, 1.0f), 0.55, 5.0, 5.0};
  if (name == "faded") return {name, Vec4f(0.97f, 0.93f, 0.80f, 1.0f), 0.15, 6.0, 6.0};
  throw InputError("bruise", "stage '" + name + "'", "unknown stage (fresh, blue, green, yellow, faded)");
}

void BruiseKey::render_into(const WoundCanvas& c, double, TiledMapSet& m) const {
  constexpr float skin_reflection = 0.25f;
  m.reset(c.width(), c.height(), skin_reflection);
  if (c.width() == 0 || c.height() == 0) return;
  ValueNoiseParams np;
  np.octaves = 4;
  np.persistence = 0.6;
  np.first_octave = std::max(0, static_cast<int>(std::lround(std::log2(std::max(c.texels_per_mm, 1.0)))));
  np.seed = mix64(c.seed ^ 0xB701);
  const ValueNoiseField mottle(c.width(), c.height(), np);
  const BruiseStage& s = m_stage;
  // The tint reaches spread_mm outside the shape; tiles beyond keep the skin.
  std::vector<CanvasTile> scratch;
  const auto& tiles = canvas_tiles(c, scratch);
  std::vector<std::pair<int, std::uint16_t*>> jobs;
  for (int t = 0; t < m.tile_count(); ++t) {
    const CanvasTile& info = tiles[static_cast<std::size_t>(t)];
    if (info.inside > 0 || info.min_outside_mm < s.spread_mm) jobs.push_back({t, m.own_color(t)});
  }
  parallel_for(
      0, jobs.size(),
      [&](std::size_t j) {
        const auto [tile, color] = jobs[j];
        const TexelRect r = m.tile_rect(tile);
        thread_local std::vector<float> noise;
        noise.resize(tiled_map_tile_texels);
        mottle.evaluate(r.x0, r.y0, r.width(), r.height(), noise.data(), tiled_map_tile);
        for (int y = r.y0; y < r.y1; ++y) {
          for (int x = r.x0; x < r.x1; ++x) {
            const std::size_t i =
                static_cast<std::size_t>(y - r.y0) * tiled_map_tile + static_cast<std::size_t>(x - r.x0);
            const bool in = c.shape.at(x, y) >= 0.5f;
            // Signed distance (mm): negative inside. Weight 1 deep inside, 0 at spread_mm outside.
            const double sd =
                in ? -static_cast<double>(c.inside_mm.at(x, y)) : static_cast<double>(c.outside_mm.at(x, y));
            double t = std::clamp((s.spread_mm - sd) / (s.spread_mm + s.inner_soft_mm), 0.0, 1.0);
            t = t * t * (3.0 - 2.0 * t);
            const float k = static_cast<float>(s.strength * t * (0.75 + 0.25 * noise[i]));
            const float* skin = c.upper_skin.pixel(x, y);
            for (std::size_t ch = 0; ch < 3; ++ch)
              color[4 * i + ch] = to_unorm16(skin[ch] * (1.0f + (s.tint[static_cast<int>(ch)] - 1.0f) * k));
            color[4 * i + 3] = to_unorm16(1.0f);
          }
        }
      },
      1);
}

nlohmann::json BruiseKey::describe() const {
  return {{"tint", {m_stage.tint.x(), m_stage.tint.y(), m_stage.tint.z()}},
          {"strength", m_stage.strength},
          {"spread_mm", m_stage.spread_mm},
          {"inner_soft_mm", m_stage.inner_soft_mm}};
}

std::vector<TimelineEntry> default_bruise_timeline() {
  const double day = 86400.0;
  auto key = [](const char* n) { return std::make_shared<BruiseKey>(bruise_stage(n)); };
  return {{0.0, key("fresh"), 0.0, "fresh (red)"},
          {1 * day, key("blue"), 0.0, "blue-purple"},
          {5 * day, key("green"), 0.0, "green"},
          {8 * day, key("yellow"), 0.0, "yellow"},
          {18 * day, key("faded"), 0.0, "faded"}};
}

double bruise_reach_mm() {
  return 6.5;
}

}  // namespace forensim
