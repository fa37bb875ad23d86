#pragma once
/// How wrinkled a skin is, to compare the wrinkle controls of Frerichs, Vidler and Gatzidis 2020 (Figure 8)
/// by numbers rather than by eye. Two measures over the skin (or a masked part of it):
/// - the RMS distance of the skin from a smoothed copy of itself (Taubin's lambda|mu smoothing with the uniform
///   Laplacian, which removes fine folds without shrinking the shape as plain Laplacian smoothing does), in mm;
/// - the mean absolute mean curvature, sum_e |theta_e| l_e / (2 A) over the edges (theta_e the dihedral angle,
///   l_e the edge length, A the area), in 1/mm: 1/r for a sphere of radius r, larger when the skin folds;
/// - the wrinkle height against a reference skin without wrinkles (the skin glued to the shrunk volume: each vertex
///   at its tracking point plus its rest offset): the RMS of the fine part of the skin's lift-off from it, so the
///   shape of the shrunk body itself, the same whatever the wrinkle controls, does not count.

#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace forensim {

struct WrinkleMeasure {
  double rms_smooth_distance_mm = 0.0;     ///< RMS |x_i - smooth(x)_i| over the (masked) vertices
  double mean_abs_curvature_per_mm = 0.0;  ///< sum |theta_e| l_e / (2 A) over the (masked) edges and area
};

/// Wrinkle measures of the skin at `positions` (#S) with `triangles`. `smoothing_steps` Taubin steps (one
/// lambda = 0.5 and one mu = -0.53 pass each). `vertex_mask` (#S, or empty for all): only vertices with mask 1,
/// edges and triangles whose vertices all have mask 1 count. Throws InputError for indices out of range or a
/// mask of the wrong size.
WrinkleMeasure wrinkle_measure(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles,
                               int smoothing_steps = 10, const std::vector<std::uint8_t>& vertex_mask = {});

/// Size of a skin's wrinkles over a reference skin without them (wrinkle_size below).
struct WrinkleSize {
  double height_mm = 0.0;  ///< RMS over the (masked) vertices of the fine lift-off f_i
  /// Wavelength 2 pi sqrt(int h^2 / int |grad h|^2) of the fine lift-off's height h_i = f_i . n_i (piecewise
  /// linear over the (masked) reference triangles): the wavelength of a sinusoidal wrinkle many edges long (four
  /// edges per wavelength read about 10 % short, a fold two edges wide about 20 %), the mean spacing of a random
  /// one. 0 when there are no wrinkles.
  double wavelength_mm = 0.0;
};

/// Wrinkle size of the skin at `positions` (#S) over `reference` (#S, same `triangles`): the fine lift-off f_i is
/// the skin's displacement along the reference's vertex normals, d_i = ((x_i - g_i) . n_i) n_i, less its
/// Taubin-smoothed copy (`smoothing_steps` as above), so the skin sliding along the surface does not count, nor
/// does a smooth lift of a whole region (wavelengths above about 13 edges pass the smoothing; two to five edges,
/// the folds the skin mesh can form, are removed by it). Throws InputError for mismatched sizes, indices out of
/// range or a bad mask.
WrinkleSize wrinkle_size(const std::vector<Vec3>& positions, const std::vector<Vec3>& reference,
                         const std::vector<Tri>& triangles, int smoothing_steps = 10,
                         const std::vector<std::uint8_t>& vertex_mask = {});

/// The fine lift-off of every vertex (#S, mm), signed along the reference's vertex normal: h_i = f_i . n_i with
/// f_i as in wrinkle_size (positive where the skin stands out of the reference, negative in a fold's trough). For
/// false-colour pictures of the wrinkles. Throws InputError for mismatched sizes or indices out of range.
std::vector<double> wrinkle_lift_off_mm(const std::vector<Vec3>& positions, const std::vector<Vec3>& reference,
                                        const std::vector<Tri>& triangles, int smoothing_steps = 10);

/// Wrinkle height of the skin at `positions` (#S) over `reference` (#S, same triangles), in mm: the skin's
/// displacement along the reference's vertex normals, d_i = ((x_i - g_i) . n_i) n_i, less its Taubin-smoothed copy
/// (`smoothing_steps` as above; smoothing is linear, so this is wrinkle_measure(d).rms_smooth_distance_mm): the
/// skin sliding along the surface does not count, nor does a smooth lift of a whole region: wrinkle_size's
/// height_mm. Throws InputError for mismatched sizes or a bad mask.
double wrinkle_height_mm(const std::vector<Vec3>& positions, const std::vector<Vec3>& reference,
                         const std::vector<Tri>& triangles, int smoothing_steps = 10,
                         const std::vector<std::uint8_t>& vertex_mask = {});

}  // namespace forensim
