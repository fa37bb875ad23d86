#pragma once
/// Element kernels of the two-layer skin shading (Frerichs, Vidler, Gatzidis 2020, section 8.3): pure
/// functions on RGB triples (linear, per channel) for the layer combination (eq. 36), the hemoglobin
/// saturation (eq. 37), the degradation level (eq. 38) and the convolution weights blended between hydrated
/// and dehydrated skin (eq. 39). The per-vertex loop is in skin_shader.hpp.

#include <array>

#include "core/types.hpp"

namespace forensim {

/// The three convolution weights of eq. 36, each an RGB triple. For every channel w1 + w2 + w3 = 1.
struct ConvolutionWeights {
  Vec3 w1 = Vec3::Zero();  ///< omega_1: epidermis seen directly
  Vec3 w2 = Vec3::Zero();  ///< omega_2: epidermis under its melanin
  Vec3 w3 = Vec3::Zero();  ///< omega_3: dermis under the melanin
};

/// Variances (mm^2) of the six Gaussians of the skin diffusion profile (d'Eon and Luebke, GPU Gems 3 ch. 14,
/// 2007) that the screen-space skin shading of Jimenez et al. 2009 (ref. 35) and the livor shader of
/// Frerichs et al. 2016 (ref. 15) convolve with: 0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41.
const std::array<double, 6>& skin_gaussian_variances_mm2();
/// The RGB weights w_1 .. w_6 of those Gaussians for hydrated skin (each channel sums to 1):
/// (0.233, 0.455, 0.649), (0.100, 0.336, 0.344), (0.118, 0.198, 0), (0.113, 0.007, 0.007), (0.358, 0.004, 0),
/// (0.078, 0, 0).
const std::array<Vec3, 6>& hydrated_gaussian_weights();
/// Hydrated weights of eq. 36: w1, w2 and w3 + w4 + w5 + w6 (eq. 39 at m = 1).
ConvolutionWeights hydrated_weights();
/// The paper's fully dehydrated weights psi (eq. 39 at m = 0): psi_1 = (0.070, 0.083, 0.100),
/// psi_2 = (0.100, 0.100, 0.100), psi_3 = (0.830, 0.817, 0.800).
ConvolutionWeights dehydrated_weights();
/// Eq. 39: omega_i = m w_i + (1 - m) psi_i for the moisture ratio m (clamped to [0, 1]).
ConvolutionWeights blended_weights(double moisture);

/// Eq. 36: c = omega_1 L_e + (1 - A_e) o (omega_2 L_e + omega_3 L_d) with o the per-channel product.
/// L_e: epidermis reflectance, L_d: dermis reflectance, A_e: melanin absorption, all linear RGB in [0, 1].
Vec3 combine_layers(const Vec3& epidermis, const Vec3& dermis, const Vec3& melanin_absorption,
                    const ConvolutionWeights& weights);

/// Melanin absorption at moisture m: the linear interpolation m A_hydrated + (1 - m) A_dehydrated (section 8.3).
Vec3 blend_melanin_absorption(const Vec3& hydrated, const Vec3& dehydrated, double moisture);

/// Eq. 37 with the paper's moisture correction: s = h M (1 + k (1 - m)), clamped to [0, 1]. h: hemoglobin
/// content (fraction of the vessels' capacity filled), M: available capacity ratio, m: moisture ratio,
/// k: relative rise of the concentration on full drying ("slightly increasing the hemoglobin saturation
/// with moisture loss"). All dimensionless.
double hemoglobin_saturation(double hemoglobin, double capacity, double moisture, double drying_boost);

/// Eq. 38: d = (o + m) / 2, the hemoglobin degradation level (1 = fresh), o the oxygen saturation and m the
/// moisture ratio, both clamped to [0, 1].
double degradation_level(double oxygen, double moisture);

}  // namespace forensim
