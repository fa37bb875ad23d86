#pragma once
/// Swatches of the skin shader's stages for pictures and reports: fresh, livor mortis, drying stages, the
/// green stage and fully dried skin. Each swatch runs from blanched skin at the top (saturation 0) to skin
/// with filled vessels at the bottom (saturation 1), so it shows the pale and the livid parts of a body at
/// that stage. Compose them into a sheet with render/sheet.hpp.

#include <string>
#include <vector>

#include "image/image.hpp"
#include "skin/skin_shader.hpp"

namespace forensim {

/// One stage: its caption and its inputs.
struct SkinStage {
  std::string caption;  ///< e.g. "livor", "m = 0.50"
  double moisture = 1.0;
  double oxygen = 0.15;  ///< o_0 of the blood
  double hours = 0.0;    ///< since the start state
};

/// The stages shown by default: fresh (oxygenated), livor (start state), drying at m = 0.75 and 0.5, the green
/// stage (green_stage_moisture()), m = 0.15 and fully dried, the last five after 240 h.
std::vector<SkinStage> default_skin_stages(const SkinShader& shader, double livor_oxygen = 0.15);

/// A width x height swatch of `stage` on uniform skin `layers` (one vertex is used): row y has saturation
/// y / (height - 1), as h with capacity 1. Display-referred (sRGB encoded, tagged srgb). Throws InputError for
/// sizes outside [2, 4096] or layers without a vertex.
Image make_skin_swatch(const SkinShader& shader, const SkinLayers& layers, const SkinStage& stage, int width,
                       int height);

}  // namespace forensim
