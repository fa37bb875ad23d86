#pragma once
/// Regular 3-D grids of scalar samples: CT and MRI volumes, distance fields. Coordinates follow ITK's and
/// NRRD's "space" conventions: world positions are patient LPS millimetres (x towards the patient's Left,
/// y towards Posterior, z towards Superior); readers convert RAS files to LPS. A voxel's value sits at its
/// centre, which is at world position origin + direction * diag(spacing) * (i, j, k) (node-centred samples,
/// as ITK, NRRD "space origin" and DICOM ImagePositionPatient define them).

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "geometry/bounding_box.hpp"

namespace forensim {

/// Most voxels a grid may hold (2^31, 8 GiB of floats); readers reject larger declared sizes before allocating.
inline constexpr std::uint64_t k_max_grid_voxels = std::uint64_t{1} << 31;
/// Most samples along one axis.
inline constexpr std::int64_t k_max_grid_axis = std::int64_t{1} << 20;

struct ScalarGrid {
  int nx = 0, ny = 0, nz = 0;         ///< samples along i, j, k
  Vec3 spacing = Vec3::Ones();        ///< mm between neighbouring samples along i, j, k (all > 0)
  Vec3 origin = Vec3::Zero();         ///< world position (LPS mm) of sample (0, 0, 0)
  Mat3 direction = Mat3::Identity();  ///< columns = unit world directions of the i, j, k axes (LPS)
  std::vector<float> values;          ///< nx*ny*nz samples, i fastest, then j, then k

  /// A grid of the given size filled with `fill`. Throws InputError when a size is not positive or the product
  /// exceeds k_max_grid_voxels.
  static ScalarGrid filled(int nx, int ny, int nz, float fill = 0.0f);

  std::size_t voxel_count() const { return std::size_t(nx) * std::size_t(ny) * std::size_t(nz); }
  /// Linear index of sample (i, j, k) in `values`.
  std::size_t linear_index(int i, int j, int k) const {
    return (std::size_t(k) * std::size_t(ny) + std::size_t(j)) * std::size_t(nx) + std::size_t(i);
  }
  float at(int i, int j, int k) const { return values[linear_index(i, j, k)]; }
  float& at(int i, int j, int k) { return values[linear_index(i, j, k)]; }

  /// 3x3 matrix M with world = origin + M * index: direction * diag(spacing).
  Mat3 index_to_world_matrix() const;
  /// World position (LPS mm) of a continuous index (i, j, k).
  Vec3 index_to_world(const Vec3& index) const;
  /// Continuous index of a world position (inverse of index_to_world).
  Vec3 world_to_index(const Vec3& world) const;
  /// Trilinear interpolation at a world position; `outside` for positions outside the sample lattice
  /// [0, n-1] on any axis.
  double sample(const Vec3& world, double outside = 0.0) const;
  /// Trilinear interpolation at a continuous index, clamped to the lattice.
  double sample_index(const Vec3& index) const;
  /// Smallest and largest finite value (NaNs ignored); (0, 0) for an empty grid.
  std::pair<float, float> value_range() const;
  /// World bounding box of the sample centres.
  BoundingBox world_bounds() const;
  /// Checks sizes against values, positive finite spacing, finite origin, an orthonormal-ish invertible
  /// direction matrix. Throws InputError naming `source` and the bad field.
  void validate(const std::string& source) const;
};

/// Number of voxels for declared sizes, after checking each is in [1, k_max_grid_axis] and the product is at most
/// k_max_grid_voxels. Throws InputError(source, location, ...) otherwise.
std::uint64_t checked_voxel_count(const std::int64_t sizes[3], const std::string& source, const std::string& location);

/// Resamples a grid onto a lattice `factor` times coarser (factor > 1) or finer (< 1) along every axis, covering the
/// same world extent, by trilinear interpolation; direction and origin are kept. Used to trade detail for speed
/// before iso-surfacing. Throws InputError for a non-positive or non-finite factor.
ScalarGrid resample_grid(const ScalarGrid& grid, double factor);

}  // namespace forensim
