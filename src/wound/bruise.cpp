#include "wound/bruise.hpp"

#include <algorithm>
#include <cmath>

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

void BruiseKey::render_into(const WoundCanvas& c, double, MapSet& m) const {
  prepare_map_set(m, c.width(), c.height(), 0.25f);
  ValueNoiseParams np;
  np.octaves = 4;
  np.persistence = 0.6;
  np.first_octave = std::max(0, static_cast<int>(std::lround(std::log2(std::max(c.texels_per_mm, 1.0)))));
  np.seed = mix64(c.seed ^ 0xB701);
  const Image mottle = value_noise(c.width(), c.height(), np);
  const BruiseStage& s = m_stage;
  parallel_for(
      0, static_cast<std::size_t>(c.height()),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        for (int x = 0; x < c.width(); ++x) {
          const bool in = c.shape.at(x, y) >= 0.5f;
          // Signed distance (mm): negative inside. Weight 1 deep inside, 0 at spread_mm outside.
          const double sd =
              in ? -static_cast<double>(c.inside_mm.at(x, y)) : static_cast<double>(c.outside_mm.at(x, y));
          double t = std::clamp((s.spread_mm - sd) / (s.spread_mm + s.inner_soft_mm), 0.0, 1.0);
          t = t * t * (3.0 - 2.0 * t);
          const float k = static_cast<float>(s.strength * t * (0.75 + 0.25 * mottle.at(x, y)));
          const Vec4f skin = c.upper_skin.rgba(x, y);
          Vec4f out;
          for (int ch = 0; ch < 3; ++ch) out[ch] = skin[ch] * (1.0f + (s.tint[ch] - 1.0f) * k);
          out.w() = 1.0f;
          m.color.set_rgba(x, y, out);
        }
      },
      8);
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
