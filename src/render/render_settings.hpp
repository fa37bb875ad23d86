#pragma once
/// Settings of one render and the display transform (exposure, filmic tone curve, sRGB).

#include <cstdint>

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

enum class ToneMap {
  aces,    ///< ACES filmic curve (Narkowicz 2015 fit): soft highlight roll-off, richer mid-tones
  linear,  ///< clamp only (for tests and data pictures)
};

struct RenderSettings {
  int width = 800;
  int height = 800;
  /// Camera samples per pixel (stratified, R2 sequence); each sample traces one shadow ray per light
  /// and one ambient-occlusion ray. 8 to 16 give clean soft shadows.
  int samples_per_pixel = 8;
  std::uint64_t seed = 1;
  /// Background colour in display (sRGB) values with alpha; alpha 0 gives a transparent PNG.
  Vec4f background = Vec4f(0.93f, 0.93f, 0.92f, 1.0f);
  /// Show the environment gradient behind the subject instead of `background`.
  bool show_environment = false;
  double exposure_stops = 0.0;  ///< multiplies linear radiance by 2^exposure_stops before tone mapping
  ToneMap tone_map = ToneMap::aces;
  bool ambient_occlusion = true;  ///< environment light with occlusion (contact shadows)
  int max_layers = 8;             ///< semi-transparent surfaces a camera ray may pass through
  int tile_size = 16;             ///< pixels per tile side (parallel work unit; does not change the result)
};

/// Display transform of one linear RGB value: exposure, tone curve, sRGB encoding; result in [0,1].
Vec3f display_transform(const Vec3f& linear, double exposure_stops, ToneMap tone_map);
/// The ACES filmic fit x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), clamped to [0,1].
float aces_filmic(float x);

}  // namespace forensim
