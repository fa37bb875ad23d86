#include "skin/chromophores.hpp"

#include <cmath>

namespace forensim {

namespace {

Spectrum gaussian_bands(std::initializer_list<std::array<double, 3>> bands) {
  Spectrum s{};
  for (int i = 0; i < spectrum_samples; ++i)
    for (const auto& [centre_nm, sigma_nm, peak] : bands) {
      const double x = (wavelength_nm(i) - centre_nm) / sigma_nm;
      s[static_cast<std::size_t>(i)] += peak * std::exp(-0.5 * x * x);
    }
  return s;
}

template <class F>
Spectrum tabulate(F f) {
  Spectrum s{};
  for (int i = 0; i < spectrum_samples; ++i) s[static_cast<std::size_t>(i)] = f(wavelength_nm(i));
  return s;
}

// S. Prahl, OMLC "Tabulated molar extinction coefficient for hemoglobin in water" (compiled from W. B. Gratzer,
// Med. Res. Council Labs, and N. Kollias, Wellman Laboratories), cm^-1/M per tetramer, 400..700 nm by 10 nm.
constexpr Spectrum oxy_table = {266232,  466816,  480360,  246072,  102580,  62816,   44480, 33209.2,
                                26629.2, 23684.4, 20932.8, 20035.2, 24202.4, 39956.8, 53236, 43016,
                                32613.2, 44496,   50104,   14400.8, 3200,    1506,    942,   610,
                                442,     368,     319.6,   294,     277.6,   276,     290};
constexpr Spectrum deoxy_table = {223296, 303956,  407560,  528600,  413280,  103292,  23388.8, 16156.4,
                                  14550,  16684,   20035.2, 25773.6, 31589.6, 39036.4, 46592,   53412,
                                  53788,  45072,   37020,   28324.4, 14677.2, 9443.6,  6509.6,  5148.8,
                                  4345.2, 3750.12, 3226.56, 2795.12, 2407.92, 2051.96, 1794.28};
// Methemoglobin (pH about 7), mM^-1 cm^-1 per heme, after the band positions and absorptivities of Zijlstra,
// Buursma and Meeuwsen-van der Roest 1991: Soret maximum near 405 nm, 500 nm band about 9, shoulder 540-580 nm,
// 630 nm band about 4, falling off towards 700 nm. Converted below to cm^-1/M per tetramer (x 4000).
constexpr Spectrum met_per_heme_mM = {150, 160, 110, 50,  25,  15,  11,  9.5, 9,   9.5, 9.0, 8.0, 6.8, 6.2, 6.3, 5.8,
                                      4.8, 4.2, 3.8, 3.4, 3.3, 3.5, 3.9, 4.0, 3.6, 2.8, 2.0, 1.4, 1.0, 0.8, 0.7};

}  // namespace

const Spectrum& molar_extinction(Chromophore chromophore) {
  static const Spectrum met = [] {
    Spectrum s{};
    for (std::size_t i = 0; i < s.size(); ++i) s[i] = 4000.0 * met_per_heme_mM[i];
    return s;
  }();
  // Band models (centre nm, sigma nm, peak cm^-1/M): biliverdin IXa absorbs violet and red and so looks green;
  // bilirubin absorbs blue and looks yellow (Randeberg et al. 2006; Prahl, OMLC bilirubin).
  static const Spectrum biliverdin = gaussian_bands({{377.0, 30.0, 50000.0}, {665.0, 45.0, 14000.0}});
  static const Spectrum bilirubin = gaussian_bands({{455.0, 33.0, 55600.0}});
  switch (chromophore) {
    case Chromophore::oxyhemoglobin:
      return oxy_table;
    case Chromophore::deoxyhemoglobin:
      return deoxy_table;
    case Chromophore::methemoglobin:
      return met;
    case Chromophore::biliverdin:
      return biliverdin;
    case Chromophore::bilirubin:
      return bilirubin;
  }
  return oxy_table;
}

const Spectrum& melanosome_absorption() {
  static const Spectrum s = tabulate([](double nm) { return 6.6e11 * std::pow(nm, -3.33); });
  return s;
}

const Spectrum& dermis_baseline_absorption() {
  static const Spectrum s = tabulate([](double nm) { return 0.244 + 85.3 * std::exp(-(nm - 154.0) / 66.2); });
  return s;
}

const Spectrum& dermis_reduced_scattering() {
  static const Spectrum s = tabulate([](double nm) { return 46.0 * std::pow(nm / 500.0, -1.421); });
  return s;
}

double diffuse_reflectance(double mu_a, double mu_s_prime, double eta) {
  const double f_dr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
  const double a = (1.0 + f_dr) / (1.0 - f_dr);
  const double albedo = mu_s_prime / (mu_a + mu_s_prime);
  const double s = std::sqrt(3.0 * (1.0 - albedo));
  return 0.5 * albedo * (1.0 + std::exp(-4.0 / 3.0 * a * s)) * std::exp(-s);
}

Vec3 spectrum_to_rgb(const Spectrum& reflectance) {
  auto band = [&](double lo, double hi) {
    double sum = 0;
    int n = 0;
    for (int i = 0; i < spectrum_samples; ++i)
      if (wavelength_nm(i) >= lo - 1e-9 && wavelength_nm(i) <= hi + 1e-9) {
        sum += reflectance[static_cast<std::size_t>(i)];
        ++n;
      }
    return sum / n;
  };
  return Vec3(band(580, 680), band(500, 570), band(430, 490));
}

Vec3 melanin_absorption(double melanin_fraction, double epidermis_mm) {
  const Spectrum& mel = melanosome_absorption();
  Spectrum transmitted{};
  const double path_cm = 2.0 * epidermis_mm * 0.1;
  for (std::size_t i = 0; i < transmitted.size(); ++i) transmitted[i] = std::exp(-melanin_fraction * mel[i] * path_cm);
  return Vec3::Ones() - spectrum_to_rgb(transmitted);
}

}  // namespace forensim
