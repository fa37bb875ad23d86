#include "volume/half_maximum_height.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"

namespace forensim {
namespace {

/// Length (mm) of one voxel along the unit world direction `n`: 1 / |M^-1 n| with M = direction * diag(spacing).
double voxel_extent(const ScalarGrid& volume, const Vec3& n) {
  const Vec3 per_mm = (volume.direction.transpose() * n).cwiseQuotient(volume.spacing);
  const double norm = per_mm.norm();
  return norm > 0.0 ? 1.0 / norm : volume.spacing.minCoeff();
}

void check(const HalfMaximumOptions& o) {
  const char* what = "half-maximum height";
  require_input(std::isfinite(o.iso_value), what, "iso-value", "is not finite");
  require_input(std::isfinite(o.peak_search_mm) && o.peak_search_mm > 0.0, what, "peak_search_mm", "must be positive");
  require_input(std::isfinite(o.background_voxels) && o.background_voxels >= 1.0, what, "background_voxels",
                "must be at least 1");
  require_input(std::isfinite(o.crossing_search_voxels) && o.crossing_search_voxels > 0.0, what,
                "crossing_search_voxels", "must be positive");
  require_input(std::isfinite(o.min_contrast) && o.min_contrast >= 0.0, what, "min_contrast", "must not be negative");
  require_input(std::isfinite(o.step_voxels) && o.step_voxels > 0.0 && o.step_voxels <= 0.5, what, "step_voxels",
                "must be in (0, 0.5]");
}

/// erf^-1(y) for y in [0, 1): Newton's method on std::erf from 0 (erf is increasing and concave on [0, inf), so the
/// iterates rise monotonically onto the root, in at most about 35 steps up to 1 - 1e-15).
double inverse_erf(double y) {
  if (!(y > 0.0)) return 0.0;
  y = std::min(y, 1.0 - 1e-15);
  double x = 0.0;
  for (int it = 0; it < 200; ++it) {
    const double step = (std::erf(x) - y) / (2.0 / std::sqrt(M_PI) * std::exp(-x * x));
    x -= step;
    if (std::abs(step) < 1e-14 * std::max(1.0, x)) break;
  }
  return x;
}

}  // namespace

double EdgeProfile::crossing_of(double level) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!found || !std::isfinite(level)) return nan;
  const auto at = [&](int k) { return double(samples[std::size_t(k)]); };
  const int last = int(samples.size()) - 1;
  // The sample just inside the iso crossing.
  const int j = std::clamp(origin + int(std::floor(crossing_mm / step_mm)), 0, last - 1);
  int m = j;
  if (at(j) >= level) {
    // The level lies outward: the last sample at or above it, walking out.
    while (m + 1 < last && at(m + 1) >= level) ++m;
  } else {
    // Inward: walk in to the first sample at or above it.
    while (m > 0 && at(m) < level) --m;
  }
  if (at(m) < level || at(m + 1) >= level) return nan;
  const double a = at(m), b = at(m + 1);
  return (m - origin + (a - level) / (a - b)) * step_mm;
}

EdgeProfile measure_edge_profile(const ScalarGrid& volume, const Vec3& point, const Vec3& outward,
                                 const HalfMaximumOptions& options) {
  EdgeProfile p;
  p.outward = outward;
  p.extent_mm = voxel_extent(volume, outward);
  const double h = options.step_voxels * p.extent_mm;
  const double search = options.crossing_search_voxels * p.extent_mm;
  const int n_in = int(std::ceil((options.peak_search_mm + search) / h));
  const int n_out = int(std::ceil((options.background_voxels * p.extent_mm + search) / h));
  p.step_mm = h;
  p.origin = n_in;
  // Outside the lattice counts as below everything (no crossing, no background there).
  const double outside = -std::numeric_limits<double>::infinity();
  const int last = n_in + n_out;
  p.samples.resize(std::size_t(last + 1));
  for (int k = 0; k <= last; ++k) {
    p.samples[std::size_t(k)] = float(volume.sample(point + (k - n_in) * h * outward, outside));
  }
  const auto at = [&](int k) { return double(p.samples[std::size_t(k)]); };
  const double iso = options.iso_value;
  // The falling iso crossing (inside at j, outside at j + 1) nearest to the point.
  int j = -1;
  const int search_steps = int(std::ceil(search / h));
  for (int d = 0; d <= search_steps && j < 0; ++d) {
    for (const int k : {n_in - d, n_in + d - 1}) {
      if (k >= 0 && k + 1 <= last && at(k) >= iso && at(k + 1) < iso && std::isfinite(at(k + 1))) {
        j = k;
        break;
      }
    }
  }
  if (j < 0) return p;
  p.crossing_mm = (j - n_in + (at(j) - iso) / (at(j) - at(j + 1))) * h;
  // The structure's peak: the highest value of the contiguous run above the iso-value, inward from j.
  int k_peak = j;
  const int k_peak_end = std::max(0, j - int(std::ceil(options.peak_search_mm / h)));
  for (int k = j; k >= k_peak_end && at(k) >= iso; --k) {
    if (at(k) > at(k_peak)) k_peak = k;
  }
  p.peak = at(k_peak);
  // The background: the plateau outside, the median of the samples one to background_voxels extents outward of
  // the crossing (the blur of the edge has died out there; the median ignores noise and a neighbour's edge).
  std::vector<double> outside_samples;
  const int k_bg_begin = j + 1 + int(std::ceil(p.extent_mm / h));
  const int k_bg_end = std::min(last, j + 1 + int(std::ceil(options.background_voxels * p.extent_mm / h)));
  for (int k = std::min(k_bg_begin, k_bg_end); k <= k_bg_end; ++k) {
    if (std::isfinite(at(k))) outside_samples.push_back(at(k));
  }
  if (outside_samples.empty()) return p;
  std::nth_element(outside_samples.begin(), outside_samples.begin() + std::ptrdiff_t(outside_samples.size() / 2),
                   outside_samples.end());
  p.background = outside_samples[outside_samples.size() / 2];
  p.found = p.peak - p.background >= options.min_contrast;
  if (!p.found) return p;
  const double near_peak = p.peak - 0.1 * (p.peak - p.background);
  int lo = k_peak, hi = k_peak;
  while (lo > 0 && at(lo - 1) >= near_peak) --lo;
  while (hi < last && at(hi + 1) >= near_peak) ++hi;
  p.plateau_mm = (hi - lo) * h;
  // The edge's 90 % to 10 % fall, outward from the peak.
  const double at_10 = p.background + 0.1 * (p.peak - p.background);
  int k90 = hi, k10 = hi;
  while (k10 < last && at(k10) > at_10) ++k10;
  p.edge_rise_mm = (k10 - k90) * h;
  return p;
}

std::vector<EdgeProfile> measure_edge_profiles(const TriMesh& surface, const ScalarGrid& volume,
                                               const HalfMaximumOptions& options) {
  check(options);
  const std::size_t n = surface.positions.size();
  const std::vector<Vec3> normals = surface.normals.size() == n ? surface.normals : vertex_normals(surface);
  std::vector<EdgeProfile> profiles(n);
  parallel_for(0, n, [&](std::size_t v) {
    const Vec3 d = normals[v].normalized();
    if (d.allFinite()) profiles[v] = measure_edge_profile(volume, surface.positions[v], d, options);
  });
  return profiles;
}

HalfMaximumHeight half_maximum_height(const std::vector<EdgeProfile>& profiles, bool plateau_only) {
  HalfMaximumHeight out;
  double sum = 0.0, sum_sq = 0.0, sum_peak = 0.0, sum_bg = 0.0;
  for (const EdgeProfile& p : profiles) {
    if (!p.found) continue;
    ++out.profiles;
    if (plateau_only && !p.is_plateau()) continue;
    ++out.used;
    const double level = p.half_maximum();
    sum += level;
    sum_sq += level * level;
    sum_peak += p.peak;
    sum_bg += p.background;
  }
  if (out.used == 0) return out;
  const double count = double(out.used);
  out.level = sum / count;
  out.level_sd = std::sqrt(std::max(0.0, sum_sq / count - out.level * out.level));
  out.peak = sum_peak / count;
  out.background = sum_bg / count;
  return out;
}

double thin_plate_level(double peak, double background, double plateau) {
  if (!(plateau > peak) || !(peak > background)) return 0.5 * (peak + background);
  const double u = inverse_erf((peak - background) / (plateau - background));
  return background + 0.5 * (plateau - background) * std::erf(2.0 * u);
}

HalfMaximumMoves move_to_half_maximum(TriMesh& surface, const std::vector<EdgeProfile>& profiles, double level,
                                      double plateau, int smoothing_iterations) {
  require_input(std::isfinite(level), "half-maximum height", "level", "is not finite");
  require_input(smoothing_iterations >= 0, "half-maximum height", "smoothing_iterations", "must not be negative");
  const std::size_t n = surface.positions.size();
  require_input(profiles.size() == n, "half-maximum height", "profiles", "must be one per surface vertex");
  HalfMaximumMoves out;
  out.vertices = n;
  if (n == 0) return out;
  std::vector<double> shift(n, 0.0);
  std::vector<char> kind(n, 0), capped(n, 0);
  parallel_for(0, n, [&](std::size_t v) {
    const EdgeProfile& p = profiles[v];
    if (!p.found) return;
    const bool reaches = p.peak > level;
    const double t = p.crossing_of(reaches ? level : thin_plate_level(p.peak, p.background, plateau));
    if (!std::isfinite(t)) return;
    kind[v] = reaches ? 1 : 2;
    capped[v] = std::abs(t) > p.extent_mm;
    shift[v] = std::clamp(t, -p.extent_mm, p.extent_mm);
  });
  // Jacobi passes of umbrella averaging: order-independent.
  const std::vector<std::array<Index, 2>> edges = unique_edges(surface.triangles);
  for (int it = 0; it < smoothing_iterations; ++it) {
    std::vector<double> sum(shift), count(n, 1.0);
    for (const auto& e : edges) {
      sum[std::size_t(e[0])] += shift[std::size_t(e[1])];
      sum[std::size_t(e[1])] += shift[std::size_t(e[0])];
      count[std::size_t(e[0])] += 1.0;
      count[std::size_t(e[1])] += 1.0;
    }
    for (std::size_t v = 0; v < n; ++v) shift[v] = sum[v] / count[v];
  }
  double sum_shift = 0.0, sum_abs = 0.0;
  for (std::size_t v = 0; v < n; ++v) {
    surface.positions[v] += shift[v] * profiles[v].outward;
    sum_shift += shift[v];
    sum_abs += std::abs(shift[v]);
    out.to_level += std::size_t(kind[v] == 1);
    out.to_own += std::size_t(kind[v] == 2);
    out.capped += std::size_t(capped[v]);
  }
  out.mean_shift_mm = sum_shift / double(n);
  out.mean_abs_shift_mm = sum_abs / double(n);
  compute_normals(surface);
  return out;
}

}  // namespace forensim
