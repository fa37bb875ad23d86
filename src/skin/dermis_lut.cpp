#include "skin/dermis_lut.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "image/exr_io.hpp"
#include "image/png_io.hpp"
#include "skin/chromophores.hpp"

namespace forensim {

namespace {

constexpr double ln10 = 2.302585092994046;
constexpr double hemoglobin_g_per_mol = 64500.0;

double smoothstep(double lo, double hi, double x) {
  if (x <= lo) return 0.0;
  if (x >= hi) return 1.0;
  const double t = (x - lo) / (hi - lo);
  return t * t * (3.0 - 2.0 * t);
}

double clamp01(double x) {
  return std::clamp(x, 0.0, 1.0);
}

void check_settings(const DermisLutSettings& s) {
  const std::string src = "dermis look-up texture settings";
  require_input(s.size_u >= 2 && s.size_u <= 4096, src, "size_u", "must be in [2, 4096]");
  require_input(s.size_v >= 3 && s.size_v <= 4097 && s.size_v % 2 == 1, src, "size_v", "must be odd, in [3, 4097]");
  auto fraction = [&](double x, const char* name) {
    require_input(std::isfinite(x) && x >= 0.0 && x <= 1.0, src, name, "must be in [0, 1]");
  };
  fraction(s.blood_fraction_min, "blood_fraction_min");
  fraction(s.blood_fraction_max, "blood_fraction_max");
  require_input(s.blood_fraction_min <= s.blood_fraction_max, src, "blood_fraction_min",
                "must not exceed blood_fraction_max");
  require_input(s.water_fraction >= 0.0 && s.water_fraction < 1.0, src, "water_fraction", "must be in [0, 1)");
  fraction(s.heme_to_biliverdin, "heme_to_biliverdin");
  fraction(s.bilirubin_fraction, "bilirubin_fraction");
  require_input(s.methemoglobin_full > 0.0 && s.methemoglobin_full <= 1.0, src, "methemoglobin_full",
                "must be in (0, 1]");
  require_input(0.0 <= s.biliverdin_onset && s.biliverdin_onset < s.biliverdin_full && s.biliverdin_full <= 1.0, src,
                "biliverdin_onset", "needs 0 <= biliverdin_onset < biliverdin_full <= 1");
  require_input(0.0 <= s.bilirubin_onset && s.bilirubin_onset < s.bilirubin_full && s.bilirubin_full <= 1.0, src,
                "bilirubin_onset", "needs 0 <= bilirubin_onset < bilirubin_full <= 1");
  require_input(std::isfinite(s.hemoglobin_g_per_l) && s.hemoglobin_g_per_l > 0.0, src, "hemoglobin_g_per_l",
                "must be positive");
  require_input(std::isfinite(s.browning_per_cm) && s.browning_per_cm >= 0.0, src, "browning_per_cm", "must be >= 0");
  require_input(std::isfinite(s.browning_decay_nm) && s.browning_decay_nm > 0.0, src, "browning_decay_nm",
                "must be positive");
  require_input(std::isfinite(s.refractive_index) && s.refractive_index >= 1.0 && s.refractive_index <= 2.0, src,
                "refractive_index", "must be in [1, 2]");
}

}  // namespace

DermisComposition dermis_composition(double s, double d, const DermisLutSettings& settings) {
  s = clamp01(s);
  d = clamp01(d);
  DermisComposition c;
  c.blood_fraction = settings.blood_fraction_min + s * (settings.blood_fraction_max - settings.blood_fraction_min);
  if (d >= 0.5) {  // hydrated: only the oxygen saturation o = 2 d - 1 changes (eq. 38 with m = 1)
    c.oxy = 2.0 * d - 1.0;
    c.deoxy = 1.0 - c.oxy;
    return c;
  }
  const double w = 1.0 - 2.0 * d;
  c.dryness = w;
  c.concentration = 1.0 / (1.0 - settings.water_fraction * w);
  const double opened =
      settings.heme_to_biliverdin * smoothstep(settings.biliverdin_onset, settings.biliverdin_full, w);
  const double reduced = settings.bilirubin_fraction * smoothstep(settings.bilirubin_onset, settings.bilirubin_full, w);
  c.biliverdin = opened * (1.0 - reduced);
  c.bilirubin = opened * reduced;
  const double heme = 1.0 - opened;
  c.met = heme * smoothstep(0.0, settings.methemoglobin_full, w);
  c.deoxy = heme - c.met;
  return c;
}

Vec3 dermis_reflectance(const DermisComposition& c, const DermisLutSettings& settings) {
  const Spectrum& oxy = molar_extinction(Chromophore::oxyhemoglobin);
  const Spectrum& deoxy = molar_extinction(Chromophore::deoxyhemoglobin);
  const Spectrum& met = molar_extinction(Chromophore::methemoglobin);
  const Spectrum& bv = molar_extinction(Chromophore::biliverdin);
  const Spectrum& br = molar_extinction(Chromophore::bilirubin);
  const Spectrum& base = dermis_baseline_absorption();
  const Spectrum& scattering = dermis_reduced_scattering();
  const double tetramer_molar = settings.hemoglobin_g_per_l / hemoglobin_g_per_mol;  // mol/L of whole blood
  const double heme_molar = 4.0 * tetramer_molar;
  Spectrum reflectance{};
  for (std::size_t i = 0; i < reflectance.size(); ++i) {
    const double blood = ln10 * (tetramer_molar * (c.oxy * oxy[i] + c.deoxy * deoxy[i] + c.met * met[i]) +
                                 heme_molar * (c.biliverdin * bv[i] + c.bilirubin * br[i]));
    const double browning = settings.browning_per_cm * c.dryness *
                            std::exp(-(wavelength_nm(static_cast<int>(i)) - 400.0) / settings.browning_decay_nm);
    const double mu_a = c.concentration * (c.blood_fraction * blood + (1.0 - c.blood_fraction) * base[i]) + browning;
    reflectance[i] = diffuse_reflectance(mu_a, scattering[i], settings.refractive_index);
  }
  return spectrum_to_rgb(reflectance);
}

Vec3 livor_dermis_colour(double s, double o, const DermisLutSettings& settings) {
  return dermis_reflectance(dermis_composition(s, 0.5 * (clamp01(o) + 1.0), settings), settings);
}

DermisLut::DermisLut(const DermisLutSettings& settings)
    : m_settings(settings), m_size_u(settings.size_u), m_size_v(settings.size_v) {
  check_settings(settings);
  m_texels.resize(static_cast<std::size_t>(m_size_u) * static_cast<std::size_t>(m_size_v));
  for (int j = 0; j < m_size_v; ++j)
    for (int i = 0; i < m_size_u; ++i) {
      const double u = static_cast<double>(i) / (m_size_u - 1);
      const double v = static_cast<double>(j) / (m_size_v - 1);
      m_texels[static_cast<std::size_t>(j) * m_size_u + i] =
          dermis_reflectance(dermis_composition(u, v, settings), settings);
    }
}

Vec3 DermisLut::sample(double u, double v) const {
  const double x = clamp01(u) * (m_size_u - 1);
  const double y = clamp01(v) * (m_size_v - 1);
  const int i0 = std::min(static_cast<int>(x), m_size_u - 2);
  const int j0 = std::min(static_cast<int>(y), m_size_v - 2);
  const double fx = x - i0, fy = y - j0;
  return (1 - fy) * ((1 - fx) * texel(i0, j0) + fx * texel(i0 + 1, j0)) +
         fy * ((1 - fx) * texel(i0, j0 + 1) + fx * texel(i0 + 1, j0 + 1));
}

Image DermisLut::image() const {
  Image image(m_size_u, m_size_v, 3);
  for (int j = 0; j < m_size_v; ++j)
    for (int i = 0; i < m_size_u; ++i) {
      const Vec3& t = texel(i, j);
      float* p = image.pixel(i, m_size_v - 1 - j);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(t[c]);
    }
  return image;
}

void write_dermis_lut(const DermisLut& lut, const std::filesystem::path& path, int scale) {
  require_input(scale >= 1 && scale <= 64, path.string(), "scale", "must be in [1, 64]");
  const Image small = lut.image();
  Image image(small.width() * scale, small.height() * scale, 3);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = small.at(x / scale, y / scale, c);
  const std::string ext = path.extension().string();
  if (ext == ".png" || ext == ".PNG")
    write_png(path, image);
  else if (ext == ".exr" || ext == ".EXR")
    write_exr(path, image, ExrPixelType::full_float);
  else
    throw InputError(path.string(), "", "look-up texture files must end in .png or .exr");
}

}  // namespace forensim
