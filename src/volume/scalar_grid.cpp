#include "volume/scalar_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace forensim {

ScalarGrid ScalarGrid::filled(int nx, int ny, int nz, float fill) {
  const std::int64_t sizes[3] = {nx, ny, nz};
  const std::uint64_t count = checked_voxel_count(sizes, "scalar grid", "sizes");
  ScalarGrid g;
  g.nx = nx;
  g.ny = ny;
  g.nz = nz;
  g.values.assign(count, fill);
  return g;
}

Mat3 ScalarGrid::index_to_world_matrix() const {
  return direction * spacing.asDiagonal();
}

Vec3 ScalarGrid::index_to_world(const Vec3& index) const {
  return origin + index_to_world_matrix() * index;
}

Vec3 ScalarGrid::world_to_index(const Vec3& world) const {
  return index_to_world_matrix().inverse() * (world - origin);
}

double ScalarGrid::sample_index(const Vec3& index) const {
  if (values.empty()) return 0.0;
  const int n[3] = {nx, ny, nz};
  int i0[3], i1[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    const double c = std::clamp(index[a], 0.0, double(n[a] - 1));
    const double f = std::floor(c);
    i0[a] = static_cast<int>(f);
    i1[a] = std::min(i0[a] + 1, n[a] - 1);
    t[a] = c - f;
  }
  const auto v = [&](int a, int b, int c) { return double(at(a, b, c)); };
  const double c00 = v(i0[0], i0[1], i0[2]) * (1 - t[0]) + v(i1[0], i0[1], i0[2]) * t[0];
  const double c10 = v(i0[0], i1[1], i0[2]) * (1 - t[0]) + v(i1[0], i1[1], i0[2]) * t[0];
  const double c01 = v(i0[0], i0[1], i1[2]) * (1 - t[0]) + v(i1[0], i0[1], i1[2]) * t[0];
  const double c11 = v(i0[0], i1[1], i1[2]) * (1 - t[0]) + v(i1[0], i1[1], i1[2]) * t[0];
  const double c0 = c00 * (1 - t[1]) + c10 * t[1];
  const double c1 = c01 * (1 - t[1]) + c11 * t[1];
  return c0 * (1 - t[2]) + c1 * t[2];
}

double ScalarGrid::sample(const Vec3& world, double outside) const {
  const Vec3 index = world_to_index(world);
  const int n[3] = {nx, ny, nz};
  constexpr double eps = 1e-9;
  for (int a = 0; a < 3; ++a) {
    if (!(index[a] >= -eps && index[a] <= n[a] - 1 + eps)) return outside;
  }
  return sample_index(index);
}

std::pair<float, float> ScalarGrid::value_range() const {
  float lo = std::numeric_limits<float>::infinity(), hi = -std::numeric_limits<float>::infinity();
  for (float v : values) {
    if (std::isnan(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (lo > hi) return {0.0f, 0.0f};
  return {lo, hi};
}

BoundingBox ScalarGrid::world_bounds() const {
  BoundingBox box;
  if (voxel_count() == 0) return box;
  for (int c = 0; c < 8; ++c) {
    const Vec3 index((c & 1) ? nx - 1 : 0, (c & 2) ? ny - 1 : 0, (c & 4) ? nz - 1 : 0);
    box.extend(index_to_world(index));
  }
  return box;
}

void ScalarGrid::validate(const std::string& source) const {
  const std::int64_t sizes[3] = {nx, ny, nz};
  const std::uint64_t count = checked_voxel_count(sizes, source, "sizes");
  require_input(values.size() == count, source, "values",
                "holds " + std::to_string(values.size()) + " values for " + std::to_string(count) + " voxels");
  for (int a = 0; a < 3; ++a) {
    require_input(
        std::isfinite(spacing[a]) && spacing[a] > 0.0, source, "spacing",
        "axis " + std::to_string(a) + " spacing " + std::to_string(spacing[a]) + " mm is not a positive finite number");
    require_input(std::isfinite(origin[a]), source, "origin", "is not finite");
  }
  require_input(direction.allFinite(), source, "direction", "is not finite");
  for (int a = 0; a < 3; ++a) {
    require_input(std::abs(direction.col(a).norm() - 1.0) < 1e-3, source, "direction",
                  "axis " + std::to_string(a) + " direction is not a unit vector");
  }
  require_input(std::abs(direction.determinant()) > 1e-3, source, "direction", "axes are (nearly) parallel");
}

std::uint64_t checked_voxel_count(const std::int64_t sizes[3], const std::string& source, const std::string& location) {
  std::uint64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    require_input(sizes[a] >= 1 && sizes[a] <= k_max_grid_axis, source, location,
                  "size " + std::to_string(sizes[a]) + " of axis " + std::to_string(a) + " is outside [1, " +
                      std::to_string(k_max_grid_axis) + "]");
    count *= static_cast<std::uint64_t>(sizes[a]);  // each <= 2^20: no overflow in 64 bits
  }
  require_input(count <= k_max_grid_voxels, source, location,
                std::to_string(count) + " voxels exceed the limit of " + std::to_string(k_max_grid_voxels));
  return count;
}

ScalarGrid resample_grid(const ScalarGrid& grid, double factor) {
  require_input(std::isfinite(factor) && factor > 0.0, "resample factor", "", "must be a positive number");
  if (factor == 1.0) return grid;
  const int n[3] = {grid.nx, grid.ny, grid.nz};
  int m[3];
  for (int a = 0; a < 3; ++a) {
    const double extent = double(n[a] - 1) / factor;
    m[a] = std::max(1, static_cast<int>(std::floor(extent + 1e-9)) + 1);
  }
  ScalarGrid out = ScalarGrid::filled(m[0], m[1], m[2]);
  out.spacing = grid.spacing * factor;
  out.origin = grid.origin;
  out.direction = grid.direction;
  for (int k = 0; k < m[2]; ++k) {
    for (int j = 0; j < m[1]; ++j) {
      for (int i = 0; i < m[0]; ++i) {
        out.at(i, j, k) = static_cast<float>(grid.sample_index(Vec3(i, j, k) * factor));
      }
    }
  }
  return out;
}

}  // namespace forensim
