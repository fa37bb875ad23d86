#pragma once
/// How uncertain a reconstructed face is (issue 8, beyond the paper: forensic artists must show what is
/// uncertain): an ensemble of reconstructions whose tissue depths are drawn from the table's means and SDs
/// (sample_tissue_depths), everything else fixed (skull, landmarks, template, guides), and per skin vertex the
/// spread of the ensemble: the RMS distance of the members' positions from their mean,
///   spread_v = sqrt(1/N sum_m |x_v^m - mean_m x_v^m|^2)  (mm).
/// Members re-target one factored warp (Reconstruction::set_depths), so a member costs one update, not a
/// fit. Member m uses RandomStream(seed, m) and members are summed in order, so the result does not depend on
/// the thread count.

#include <cstdint>
#include <vector>

#include "craniofacial/reconstruction.hpp"

namespace forensim {

struct ReconstructionUncertainty {
  int samples = 0;
  std::uint64_t seed = 0;
  std::vector<Vec3> mean_positions;      ///< #V mean skin vertex positions of the ensemble, mm
  std::vector<double> vertex_spread_mm;  ///< #V RMS distance from the mean, mm
  double max_spread_mm = 0.0;
  double mean_spread_mm = 0.0;  ///< mean over vertices
};

/// The ensemble of `samples` members around `reconstruction` (its skull, landmarks, depths and options; the
/// object itself is left as it was: it is restored to its depths afterwards). Throws InputError for samples
/// outside [2, 10000] or depths without SDs (naming the site).
ReconstructionUncertainty reconstruction_uncertainty(Reconstruction& reconstruction, int samples, std::uint64_t seed);

}  // namespace forensim
