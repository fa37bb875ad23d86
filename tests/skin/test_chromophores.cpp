// Spectral optics of the chromophores: the reflectance model's monotonicity and limits, the RGB reduction, the
// melanin absorption and the features of the hemoglobin spectra the shading depends on.

#include <gtest/gtest.h>

#include <cmath>

#include "skin/chromophores.hpp"

using namespace forensim;

namespace {
std::size_t sample_at(double nm) {
  return static_cast<std::size_t>(std::lround((nm - 400.0) / 10.0));
}
}  // namespace

TEST(Chromophores, DiffuseReflectanceFallsWithAbsorptionAndIsBounded) {
  double previous = diffuse_reflectance(0.0, 30.0);
  EXPECT_NEAR(previous, 1.0, 1e-12);  // without absorption all light comes back out
  for (double mu_a = 0.01; mu_a < 1000.0; mu_a *= 1.5) {
    const double r = diffuse_reflectance(mu_a, 30.0);
    EXPECT_LT(r, previous) << mu_a;
    EXPECT_GT(r, 0.0);
    previous = r;
  }
  // Only the albedo matters: scaling both coefficients leaves R_d unchanged.
  EXPECT_NEAR(diffuse_reflectance(2.0, 30.0), diffuse_reflectance(20.0, 300.0), 1e-14);
}

TEST(Chromophores, FlatSpectrumIsGrey) {
  Spectrum flat;
  flat.fill(0.37);
  const Vec3 rgb = spectrum_to_rgb(flat);
  EXPECT_NEAR(rgb[0], 0.37, 1e-15);
  EXPECT_NEAR(rgb[1], 0.37, 1e-15);
  EXPECT_NEAR(rgb[2], 0.37, 1e-15);
}

TEST(Chromophores, MelaninAbsorbsBlueMostAndGrowsWithTheFraction) {
  Vec3 previous = melanin_absorption(0.0);
  EXPECT_NEAR(previous.norm(), 0.0, 1e-15);
  for (double f : {0.01, 0.03, 0.1, 0.3}) {
    const Vec3 a = melanin_absorption(f);
    EXPECT_GT(a[2], a[1]);
    EXPECT_GT(a[1], a[0]);
    EXPECT_TRUE((a.array() > previous.array()).all()) << f;
    EXPECT_LT(a.maxCoeff(), 1.0);
    previous = a;
  }
}

TEST(Chromophores, HemoglobinSpectraHaveTheirKnownFeatures) {
  const Spectrum& oxy = molar_extinction(Chromophore::oxyhemoglobin);
  const Spectrum& deoxy = molar_extinction(Chromophore::deoxyhemoglobin);
  // Deoxyhemoglobin absorbs red light several times more than oxyhemoglobin (why hypostasis is bluish).
  for (double nm = 620; nm <= 700; nm += 10) EXPECT_GT(deoxy[sample_at(nm)], 5.0 * oxy[sample_at(nm)]) << nm;
  // Oxyhemoglobin's Q bands at about 540 and 576 nm are local maxima; deoxy has one band near 555 nm.
  EXPECT_GT(oxy[sample_at(540)], oxy[sample_at(560)]);
  EXPECT_GT(oxy[sample_at(580)], oxy[sample_at(560)]);
  EXPECT_GT(deoxy[sample_at(560)], deoxy[sample_at(530)]);
  EXPECT_GT(deoxy[sample_at(560)], deoxy[sample_at(590)]);
  // Biliverdin absorbs red more than green (green), bilirubin blue more than green (yellow).
  const Spectrum& bv = molar_extinction(Chromophore::biliverdin);
  const Spectrum& br = molar_extinction(Chromophore::bilirubin);
  EXPECT_GT(bv[sample_at(660)], 3.0 * bv[sample_at(530)]);
  EXPECT_GT(br[sample_at(460)], 10.0 * br[sample_at(560)]);
  // Methemoglobin's 630 nm band.
  const Spectrum& met = molar_extinction(Chromophore::methemoglobin);
  EXPECT_GT(met[sample_at(630)], met[sample_at(600)]);
  EXPECT_GT(met[sample_at(630)], met[sample_at(660)]);
}
