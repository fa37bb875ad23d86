#pragma once
/// The dermis colour look-up texture of the mummification skin shader (Frerichs et al. 2020, section 8.3,
/// Figure 3), generated from the absorption of the blood's chromophores rather than painted.
///
/// Axes:
/// - u = s, the hemoglobin saturation of eq. 37 (the fraction of the dermis's blood capacity that is filled),
///   mapped to a dermal blood volume fraction B = B_min + s (B_max - B_min);
/// - v = d, the hemoglobin degradation level of eq. 38, d = (o + m) / 2 with o the oxygen saturation of the
///   blood and m the moisture ratio. v = 1 is fresh, oxygenated, hydrated blood; v = 1/2 fully deoxygenated
///   and hydrated (livor mortis); below 1/2 the skin is drying, and with the dryness w = 1 - 2 v
///   (= 1 - m once the oxygen is used up) the heme degrades:
///     deoxyhemoglobin -> methemoglobin (brown; complete at w = methemoglobin_full),
///     part of the heme (heme_to_biliverdin) opened to biliverdin (green; between biliverdin_onset and
///     biliverdin_full), which is then reduced to bilirubin (yellow; bilirubin_fraction of it between
///     bilirubin_onset and bilirubin_full),
///   while the water loss concentrates every absorber by 1 / (1 - water_fraction w) and dried protein browns
///   (an absorber browning_per_cm w exp(-(lambda - 400) / browning_decay_nm), as Maillard melanoidins).
///   The green stage is forensim's addition beyond the paper (its Figure 10b: the greenish discoloration of
///   a partly dried leg that the paper could not reproduce; the sequence follows bruise healing, its ref. 38).
///
/// Per texel, the absorption mu_a(lambda) = C (B sum_k c_k eps_k ln10 + (1 - B) mu_a,baseline) + mu_a,brown is
/// turned into a diffuse reflectance with the dermis scattering (chromophores.hpp) and reduced to linear RGB.
/// As designed: along u every channel decreases (more blood absorbs more at every wavelength); along v, from
/// 1 down to 0, the luminance decreases (deoxygenation, then drying darken), while the hue passes from red
/// to bluish purple, brown, olive-green and dark brown.

#include <filesystem>

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

/// Parameters of the generated look-up texture. Dimensionless unless the name says otherwise.
struct DermisLutSettings {
  int size_u = 64;                    ///< texels along u (saturation), >= 2; texel i holds u = i / (size_u - 1)
  int size_v = 65;                    ///< texels along v (degradation), >= 3 and odd so that v = 1/2 is a texel row
  double blood_fraction_min = 0.002;  ///< B_min: dermal blood volume fraction at s = 0 (blanched skin)
  double blood_fraction_max = 0.08;   ///< B_max: at s = 1 (capillaries filled by hypostasis)
  double hemoglobin_g_per_l = 150.0;  ///< hemoglobin of whole blood, g/L (64 500 g/mol)
  double water_fraction = 0.65;       ///< water volume fraction of the dermis lost on full drying
  double methemoglobin_full = 0.7;    ///< dryness at which the remaining heme is all methemoglobin
  double heme_to_biliverdin = 0.35;   ///< fraction of the heme broken down to biliverdin (0 = no green stage)
  double biliverdin_onset = 0.1, biliverdin_full = 0.55;  ///< dryness range of the heme breakdown
  double bilirubin_fraction = 0.8;                        ///< part of the biliverdin reduced to bilirubin
  double bilirubin_onset = 0.35, bilirubin_full = 0.8;    ///< dryness range of that reduction
  double browning_per_cm = 16.0;    ///< mu_a of browned dry protein at 400 nm when fully dried, cm^-1
  double browning_decay_nm = 90.0;  ///< its fall-off with wavelength
  double refractive_index = 1.4;    ///< of the dermis, for the diffuse Fresnel term
};

/// Amounts of the absorbers in one texel.
struct DermisComposition {
  double blood_fraction = 0.0;  ///< B, dermal blood volume fraction
  double dryness = 0.0;         ///< w in [0, 1]
  double concentration = 1.0;   ///< 1 / (1 - water_fraction w)
  /// Fractions of the blood's heme (sum 1): oxy-, deoxy- and methemoglobin, biliverdin, bilirubin.
  double oxy = 0.0, deoxy = 0.0, met = 0.0, biliverdin = 0.0, bilirubin = 0.0;
};

/// The composition at saturation `s` and degradation level `d` (both clamped to [0, 1]), as described above.
DermisComposition dermis_composition(double s, double d, const DermisLutSettings& settings = {});
/// Linear RGB diffuse reflectance of the dermis with that composition.
Vec3 dermis_reflectance(const DermisComposition& composition, const DermisLutSettings& settings = {});
/// The dermis colour of hydrated skin as the livor mortis shader of Frerichs et al. 2016 indexes it, by
/// saturation s and oxygen saturation o (both [0, 1]): the same as dermis_reflectance at d = (o + 1) / 2.
Vec3 livor_dermis_colour(double s, double o, const DermisLutSettings& settings = {});

/// The generated look-up texture: size_u x size_v linear RGB texels, sampled bilinearly.
class DermisLut {
 public:
  /// Generates the texture (deterministic: a pure function of `settings`). Throws InputError for sizes or
  /// parameters out of range (sizes as documented, fractions outside [0, 1], onset >= full, B_min > B_max).
  explicit DermisLut(const DermisLutSettings& settings = {});
  /// Bilinear lookup at (u, v), both clamped to [0, 1].
  Vec3 sample(double u, double v) const;
  /// Texel (i, j): u = i / (size_u - 1), v = j / (size_v - 1).
  const Vec3& texel(int i, int j) const { return m_texels[static_cast<std::size_t>(j) * m_size_u + i]; }
  int size_u() const { return m_size_u; }
  int size_v() const { return m_size_v; }
  const DermisLutSettings& settings() const { return m_settings; }
  /// The texture as a linear RGB image, u to the right and v up (row 0 is v = 1), as in the paper's Figure 3.
  Image image() const;

 private:
  DermisLutSettings m_settings;
  int m_size_u = 0, m_size_v = 0;
  std::vector<Vec3> m_texels;  ///< size_u * size_v, v-major
};

/// Writes the texture: `.png` as 8-bit sRGB, `.exr` as 32-bit float linear (by the extension; InputError for
/// any other), atomically. `scale` repeats each texel scale x scale times (nearest) for viewing.
void write_dermis_lut(const DermisLut& lut, const std::filesystem::path& path, int scale = 1);

}  // namespace forensim
