#include "craniofacial/reconstruction_uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {

ReconstructionUncertainty reconstruction_uncertainty(Reconstruction& reconstruction, int samples, std::uint64_t seed) {
  require_input(samples >= 2 && samples <= 10000, "uncertainty", "samples",
                "must be between 2 and 10000, got " + std::to_string(samples));
  const TissueDepths base = reconstruction.depths();
  const std::size_t n = reconstruction.result().skin.positions.size();
  std::vector<std::vector<Vec3>> members;
  members.reserve(static_cast<std::size_t>(samples));
  for (int m = 0; m < samples; ++m) {
    reconstruction.set_depths(sample_tissue_depths(base, seed, static_cast<std::uint64_t>(m)));
    members.push_back(reconstruction.result().skin.positions);
  }
  reconstruction.set_depths(base);
  ReconstructionUncertainty out;
  out.samples = samples;
  out.seed = seed;
  out.mean_positions.assign(n, Vec3::Zero());
  out.vertex_spread_mm.assign(n, 0.0);
  // Per vertex, members in order: the same sums at any thread count.
  parallel_for(0, n, [&](std::size_t v) {
    Vec3 mean = Vec3::Zero();
    for (const auto& x : members) mean += x[v];
    mean /= static_cast<double>(samples);
    double sum = 0.0;
    for (const auto& x : members) sum += (x[v] - mean).squaredNorm();
    out.mean_positions[v] = mean;
    out.vertex_spread_mm[v] = std::sqrt(sum / static_cast<double>(samples));
  });
  double total = 0.0;
  for (const double s : out.vertex_spread_mm) {
    out.max_spread_mm = std::max(out.max_spread_mm, s);
    total += s;
  }
  out.mean_spread_mm = n > 0 ? total / static_cast<double>(n) : 0.0;
  return out;
}

}  // namespace forensim
