#pragma once
/// Spectral optics of skin chromophores on a 10 nm grid from 400 to 700 nm: the absorption of oxy-, deoxy- and
/// methemoglobin, the hemoglobin breakdown products biliverdin (green) and bilirubin (yellow), melanin and the
/// bloodless dermis, the reduced scattering of the dermis, the diffuse reflectance of a scattering half-space
/// and the reduction of a spectrum to linear RGB. The look-up textures of the layered skin shading
/// (dermis_lut.hpp) are computed from these, so that their colours follow from absorption and are not painted.
///
/// Sources of the coefficients (cited again at each table in chromophores.cpp):
/// - oxy- and deoxyhemoglobin: S. Prahl, "Optical absorption of hemoglobin" (OMLC, 1999), compiled from
///   W. B. Gratzer and N. Kollias; molar extinction per mole of hemoglobin tetramer (64 500 g/mol);
/// - methemoglobin: the band positions and absorptivities of W. G. Zijlstra, A. Buursma and
///   W. P. Meeuwsen-van der Roest, "Absorption spectra of human fetal and adult oxyhemoglobin,
///   de-oxyhemoglobin, carboxyhemoglobin, and methemoglobin", Clin. Chem. 37 (1991) 1633-1638
///   (Soret band near 405 nm, bands at 500 nm (about 9 mM^-1 cm^-1 per heme) and 630 nm (about 4));
/// - biliverdin and bilirubin: band models (Gaussian bands at the reported maxima and peak molar
///   absorptivities) as used in bruise spectroscopy: L. L. Randeberg et al., "A novel approach to age
///   determination of traumatic injuries by reflectance spectroscopy", Lasers Surg. Med. 38 (2006) 277-289,
///   and L. Vidovic, M. Milanic, B. Majaron (ref. 37 of Frerichs et al. 2020); bilirubin one band near
///   450-460 nm of about 55 600 M^-1 cm^-1 (S. Prahl, OMLC, bilirubin in chloroform), modelled at 455 nm with
///   a 33 nm standard deviation; biliverdin bands near 377 nm (about 50 000) and 665 nm (about 14 000 M^-1 cm^-1).
///   These three are approximations of the published curves at their key values, not measured tables;
/// - melanin, dermis baseline and dermis scattering: S. L. Jacques, "Skin optics" (OMLC News, 1998) and
///   "Optical properties of biological tissues: a review", Phys. Med. Biol. 58 (2013) R37-R61;
/// - diffuse reflectance: the dipole diffusion approximation of H. W. Jensen, S. R. Marschner, M. Levoy and
///   P. Hanrahan, "A practical model for subsurface light transport", SIGGRAPH 2001 (their eq. for R_d).

#include <array>

#include "core/types.hpp"

namespace forensim {

/// Number of spectral samples: 400, 410, ..., 700 nm.
inline constexpr int spectrum_samples = 31;
/// A quantity sampled at the wavelengths wavelength_nm(0..30).
using Spectrum = std::array<double, spectrum_samples>;

/// Wavelength of sample i in nm (400 + 10 i).
constexpr double wavelength_nm(int i) {
  return 400.0 + 10.0 * i;
}

/// The absorbers of the dermis and epidermis that the look-up textures mix.
enum class Chromophore {
  oxyhemoglobin,    ///< HbO2, bright red
  deoxyhemoglobin,  ///< Hb, dark bluish red (livor mortis)
  methemoglobin,    ///< ferric hemoglobin (metHb), brown: autoxidation of dead and drying blood
  biliverdin,       ///< first heme breakdown product, green
  bilirubin,        ///< reduced biliverdin, yellow
};

/// Molar extinction coefficient epsilon(lambda) in cm^-1 / (mol/L), decadic (absorbance = epsilon c l).
/// Hemoglobins: per mole of tetramer (four hemes); biliverdin and bilirubin: per mole of molecule (one per
/// heme broken down).
const Spectrum& molar_extinction(Chromophore chromophore);

/// Absorption coefficient mu_a (cm^-1) of the melanosome interior: 6.6e11 lambda^-3.33, lambda in nm (Jacques).
const Spectrum& melanosome_absorption();
/// Absorption coefficient mu_a (cm^-1) of bloodless dermis: 0.244 + 85.3 exp(-(lambda - 154) / 66.2) (Jacques).
const Spectrum& dermis_baseline_absorption();
/// Reduced scattering coefficient mu_s' (cm^-1) of dermis: 46 (lambda / 500 nm)^-1.421 (Jacques 2013, skin).
const Spectrum& dermis_reduced_scattering();

/// Total diffuse reflectance R_d of a semi-infinite scattering medium (Jensen et al. 2001, dipole):
/// R_d = a'/2 (1 + exp(-4/3 A sqrt(3 (1 - a')))) exp(-sqrt(3 (1 - a'))), a' = mu_s' / (mu_a + mu_s'),
/// A = (1 + F_dr) / (1 - F_dr) with the diffuse Fresnel reflectance F_dr of relative index `eta`.
/// mu_a, mu_s' in the same unit (cm^-1); mu_a >= 0, mu_s' > 0. Decreases strictly with mu_a.
double diffuse_reflectance(double mu_a, double mu_s_prime, double eta = 1.4);

/// Linear RGB of a reflectance spectrum: each channel is the mean over its band (blue 430-490 nm, green
/// 500-570 nm, red 580-680 nm). A spectrum that is the same at every wavelength gives grey of that value.
Vec3 spectrum_to_rgb(const Spectrum& reflectance);

/// Epidermal melanin absorption A_e (eq. 36) per RGB channel for a melanosome volume fraction
/// `melanin_fraction` (0..1; about 0.01-0.06 in light, 0.11-0.16 in medium, 0.18-0.43 in dark skin, Jacques
/// 1998) in an epidermis `epidermis_mm` thick: the band mean of 1 - exp(-2 f mu_a,mel t), the light crossing the
/// layer down and up again. Every channel in [0, 1); blue largest.
Vec3 melanin_absorption(double melanin_fraction, double epidermis_mm = 0.08);

}  // namespace forensim
