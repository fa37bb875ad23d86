#pragma once
/// The mummification skin shader (Frerichs, Vidler, Gatzidis 2020, section 8.3) per skin vertex: two layers,
/// epidermis and dermis, combined by eq. 36 with the convolution weights of eq. 39; the dermis colour from the
/// generated look-up texture (dermis_lut.hpp) at the hemoglobin saturation of eq. 37 and the degradation
/// level of eq. 38; the melanin absorption interpolated between its hydrated and dehydrated values. The start
/// state is the livor mortis state (livor_mortis.hpp).
///
/// Time since the start state enters through the oxygen left in the settled blood, o(t) = o_0 exp(-t / tau_O2)
/// (post-mortem consumption by the tissue; beyond the paper, which keeps o from its livor simulation), so d of
/// eq. 38 falls to m / 2 and the look-up follows the heme's degradation as the skin dries.
///
/// The spatial part of the screen-space subsurface convolution (the Gaussians' blur, Jimenez et al. 2009) is
/// the renderer's; per vertex, the weights give the colour the blurred layers sum to on a uniform patch.

#include <vector>

#include "core/types.hpp"
#include "skin/dermis_lut.hpp"
#include "skin/livor_mortis.hpp"
#include "skin/skin_layers.hpp"

namespace forensim {

/// Settings of the shader. Dimensionless unless the name says otherwise.
struct SkinShadingSettings {
  DermisLutSettings lut;       ///< the generated dermis look-up texture
  double drying_boost = 0.25;  ///< k of eq. 37: relative rise of the saturation on full drying
  /// tau_O2: e-folding time of the blood's oxygen after the start state. Times are counted from the livor
  /// start state (fixed hypostasis, some 8 to 12 hours after death), which is time 0 of the drying run.
  double oxygen_decay_hours = 12.0;
};

/// Fixed per-vertex skin data (#V entries each): the epidermis reflectance map and the two-channel melanin map
/// of section 8.3, with the absorptions derived from it.
struct SkinLayers {
  std::vector<Vec3> vertex_epidermis;              ///< L_e: linear RGB reflectance without hemoglobin, [0, 1]
  std::vector<double> vertex_melanin_hydrated;     ///< melanosome volume fraction, hydrated skin, [0, 1]
  std::vector<double> vertex_melanin_dehydrated;   ///< the same for fully dried skin
  std::vector<Vec3> vertex_absorption_hydrated;    ///< A_e of the hydrated fraction (melanin_absorption())
  std::vector<Vec3> vertex_absorption_dehydrated;  ///< A_e of the dehydrated fraction
  std::size_t size() const { return vertex_epidermis.size(); }
};

/// Skin layers from per-vertex maps: `epidermis` (#V linear RGB) and `melanin_hydrated` (#V melanosome
/// fractions). The dehydrated channel is `dehydrated_factor` times the hydrated one (clamped to 1): dried
/// epidermis absorbs more, which the paper's second melanin channel encodes (4 gives the blackish brown of
/// fully dried skin). `epidermis_mm` is the thickness of the layer the melanin lies in (melanin_absorption()).
/// Throws InputError for sizes or values out of range.
SkinLayers make_skin_layers(const std::vector<Vec3>& epidermis, const std::vector<double>& melanin_hydrated,
                            double dehydrated_factor = 4.0, double epidermis_mm = 0.08);
/// Uniform skin layers for `vertices` vertices: a light skin (L_e = (0.85, 0.56, 0.43), melanin 0.03).
SkinLayers uniform_skin_layers(std::size_t vertices, const Vec3& epidermis = Vec3(0.85, 0.56, 0.43),
                               double melanin_hydrated = 0.03, double dehydrated_factor = 4.0,
                               double epidermis_mm = 0.08);

/// The shader: generates its look-up texture once in the constructor, then shades frames cheaply.
class SkinShader {
 public:
  /// Throws InputError for settings out of range.
  explicit SkinShader(const SkinShadingSettings& settings = {});

  /// Colour (linear RGB) of one vertex. `epidermis`: L_e; `absorption_hydrated`/`_dehydrated`: A_e at m = 1
  /// and 0; `hemoglobin` h, `capacity` M, `oxygen` o_0 from the livor state; `moisture` m in [0, 1] (moisture
  /// over its initial value); `hours` since the start state (>= 0).
  Vec3 shade_vertex(const Vec3& epidermis, const Vec3& absorption_hydrated, const Vec3& absorption_dehydrated,
                    double hemoglobin, double capacity, double oxygen, double moisture, double hours) const;

  /// Colours of every vertex (#V linear RGBA, alpha 1) into `colours` (resized). `vertex_moisture`: #V moisture
  /// ratios m (clamped to [0, 1]). Parallel, deterministic. Throws InputError for mismatched sizes or a negative
  /// or non-finite time.
  void shade(const SkinLayers& layers, const LivorState& livor, const std::vector<double>& vertex_moisture,
             double hours, std::vector<Vec4f>& colours) const;
  std::vector<Vec4f> shade(const SkinLayers& layers, const LivorState& livor,
                           const std::vector<double>& vertex_moisture, double hours) const;

  /// o(t) = o_0 exp(-t / tau_O2).
  double oxygen_at(double oxygen, double hours) const;
  const DermisLut& lut() const { return m_lut; }
  const SkinShadingSettings& settings() const { return m_settings; }

 private:
  SkinShadingSettings m_settings;
  DermisLut m_lut;
};

/// The livor mortis colours of the start state as the 2016 livor shader gives them: eq. 36 with the hydrated
/// weights, the hydrated melanin and the dermis colour computed directly from the chromophores at (s, o)
/// (livor_dermis_colour(), no look-up texture). #V linear RGBA.
std::vector<Vec4f> livor_colours(const SkinLayers& layers, const LivorState& livor,
                                 const SkinShadingSettings& settings = {});

/// The moisture ratio at which drying skin of saturation `saturation` (o = 0) is greenest (largest G / R),
/// searched on a grid of `steps` (the green stage of the look-up texture; 1 when there is none).
double green_stage_moisture(const SkinShader& shader, double saturation = 1.0, int steps = 200);

}  // namespace forensim
