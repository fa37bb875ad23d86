#include "skin/skin_layers.hpp"

#include <algorithm>

namespace forensim {

namespace {
double clamp01(double x) {
  return std::clamp(x, 0.0, 1.0);
}
}  // namespace

const std::array<double, 6>& skin_gaussian_variances_mm2() {
  static const std::array<double, 6> v = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
  return v;
}

const std::array<Vec3, 6>& hydrated_gaussian_weights() {
  static const std::array<Vec3, 6> w = {Vec3(0.233, 0.455, 0.649), Vec3(0.100, 0.336, 0.344), Vec3(0.118, 0.198, 0.0),
                                        Vec3(0.113, 0.007, 0.007), Vec3(0.358, 0.004, 0.0),   Vec3(0.078, 0.0, 0.0)};
  return w;
}

ConvolutionWeights hydrated_weights() {
  const auto& w = hydrated_gaussian_weights();
  return {w[0], w[1], w[2] + w[3] + w[4] + w[5]};
}

ConvolutionWeights dehydrated_weights() {
  return {Vec3(0.070, 0.083, 0.100), Vec3(0.100, 0.100, 0.100), Vec3(0.830, 0.817, 0.800)};
}

ConvolutionWeights blended_weights(double moisture) {
  const double m = clamp01(moisture);
  const ConvolutionWeights w = hydrated_weights(), psi = dehydrated_weights();
  return {m * w.w1 + (1 - m) * psi.w1, m * w.w2 + (1 - m) * psi.w2, m * w.w3 + (1 - m) * psi.w3};
}

Vec3 combine_layers(const Vec3& epidermis, const Vec3& dermis, const Vec3& melanin_absorption,
                    const ConvolutionWeights& weights) {
  return weights.w1.cwiseProduct(epidermis) +
         (Vec3::Ones() - melanin_absorption)
             .cwiseProduct(weights.w2.cwiseProduct(epidermis) + weights.w3.cwiseProduct(dermis));
}

Vec3 blend_melanin_absorption(const Vec3& hydrated, const Vec3& dehydrated, double moisture) {
  const double m = clamp01(moisture);
  return m * hydrated + (1 - m) * dehydrated;
}

double hemoglobin_saturation(double hemoglobin, double capacity, double moisture, double drying_boost) {
  return clamp01(hemoglobin * capacity * (1.0 + drying_boost * (1.0 - clamp01(moisture))));
}

double degradation_level(double oxygen, double moisture) {
  return 0.5 * (clamp01(oxygen) + clamp01(moisture));
}

}  // namespace forensim
