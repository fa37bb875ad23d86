#include "render/render_settings.hpp"

#include <algorithm>
#include <cmath>

#include "image/color.hpp"

namespace forensim {

float aces_filmic(float x) {
  if (!(x > 0.0f)) return 0.0f;
  const float y = x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f);
  return std::clamp(y, 0.0f, 1.0f);
}

Vec3f display_transform(const Vec3f& linear, double exposure_stops, ToneMap tone_map) {
  const float scale = static_cast<float>(std::exp2(exposure_stops));
  Vec3f out;
  for (int c = 0; c < 3; ++c) {
    float v = linear[c] * scale;
    // The ACES fit brightens mid-tones (0.18 -> 0.27); a 0.72 pre-gain keeps a mid-grey card at 0.18.
    v = tone_map == ToneMap::aces ? aces_filmic(0.72f * v) : std::clamp(v, 0.0f, 1.0f);
    out[c] = linear_to_srgb(v);
  }
  return out;
}

}  // namespace forensim
