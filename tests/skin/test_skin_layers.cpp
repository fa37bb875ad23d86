// Kernels of the layered skin: the convolution weights of eq. 39 blend exactly between the hydrated
// Gaussians and the paper's psi, each channel sums to one, and eqs. 36 to 38.

#include <gtest/gtest.h>

#include "skin/skin_layers.hpp"

using namespace forensim;

TEST(SkinLayers, HydratedWeightsAreTheSixGaussiansAndSumToOne) {
  const auto& g = hydrated_gaussian_weights();
  Vec3 sum = Vec3::Zero();
  for (const Vec3& w : g) sum += w;
  EXPECT_LT((sum - Vec3::Ones()).norm(), 1e-12);
  const ConvolutionWeights w = hydrated_weights();
  EXPECT_EQ(w.w1, g[0]);
  EXPECT_EQ(w.w2, g[1]);
  EXPECT_LT((w.w3 - (g[2] + g[3] + g[4] + g[5])).norm(), 1e-15);
  const ConvolutionWeights psi = dehydrated_weights();
  EXPECT_LT((psi.w1 + psi.w2 + psi.w3 - Vec3::Ones()).norm(), 1e-12);
  // The paper: psi_1 and psi_2 below w_1 and w_2 (thinner, more translucent epidermis when dried).
  EXPECT_TRUE((psi.w1.array() < w.w1.array()).all());
  EXPECT_TRUE((psi.w2.array() <= w.w2.array()).all());
  const auto& variances = skin_gaussian_variances_mm2();
  for (std::size_t i = 1; i < variances.size(); ++i) EXPECT_GT(variances[i], variances[i - 1]);
}

TEST(SkinLayers, Eq39BlendsExactlyBetweenHydratedAndDehydrated) {
  const ConvolutionWeights w = hydrated_weights(), psi = dehydrated_weights();
  const ConvolutionWeights at1 = blended_weights(1.0), at0 = blended_weights(0.0);
  EXPECT_EQ(at1.w1, w.w1);
  EXPECT_EQ(at1.w3, w.w3);
  EXPECT_EQ(at0.w1, psi.w1);
  EXPECT_EQ(at0.w2, psi.w2);
  EXPECT_EQ(at0.w3, psi.w3);
  EXPECT_EQ(blended_weights(1.7).w2, w.w2);  // clamped
  for (double m : {0.1, 0.25, 0.5, 0.9}) {
    const ConvolutionWeights b = blended_weights(m);
    EXPECT_LT((b.w1 - (m * w.w1 + (1 - m) * psi.w1)).norm(), 1e-15);
    EXPECT_LT((b.w2 - (m * w.w2 + (1 - m) * psi.w2)).norm(), 1e-15);
    EXPECT_LT((b.w3 - (m * w.w3 + (1 - m) * psi.w3)).norm(), 1e-15);
    EXPECT_LT((b.w1 + b.w2 + b.w3 - Vec3::Ones()).norm(), 1e-12) << m;
  }
}

TEST(SkinLayers, Eq36ReproducesEqualLayersWithoutMelaninAndDimsWithIt) {
  const Vec3 x(0.6, 0.4, 0.3);
  for (double m : {0.0, 0.5, 1.0})
    EXPECT_LT((combine_layers(x, x, Vec3::Zero(), blended_weights(m)) - x).norm(), 1e-12);
  const ConvolutionWeights w = hydrated_weights();
  const Vec3 le(0.8, 0.6, 0.5), ld(0.5, 0.2, 0.2), a(0.2, 0.3, 0.4);
  const Vec3 c = combine_layers(le, ld, a, w);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(c[k], w.w1[k] * le[k] + (1 - a[k]) * (w.w2[k] * le[k] + w.w3[k] * ld[k]), 1e-15);
  // Full melanin absorption leaves only the directly reflected epidermis.
  EXPECT_LT((combine_layers(le, ld, Vec3::Ones(), w) - w.w1.cwiseProduct(le)).norm(), 1e-15);
}

TEST(SkinLayers, SaturationAndDegradationFollowEqs37And38) {
  EXPECT_DOUBLE_EQ(hemoglobin_saturation(0.5, 0.8, 1.0, 0.25), 0.4);
  EXPECT_DOUBLE_EQ(hemoglobin_saturation(0.5, 0.8, 0.0, 0.25), 0.5);
  EXPECT_DOUBLE_EQ(hemoglobin_saturation(1.0, 1.0, 0.0, 0.25), 1.0);  // clamped
  EXPECT_DOUBLE_EQ(degradation_level(0.2, 0.6), 0.4);
  EXPECT_DOUBLE_EQ(degradation_level(1.0, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(degradation_level(-1.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(blend_melanin_absorption(Vec3(0.2, 0.2, 0.2), Vec3(0.6, 0.6, 0.6), 0.25)[1], 0.5);
}
