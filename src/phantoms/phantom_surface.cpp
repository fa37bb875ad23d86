#include "phantoms/phantom_surface.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "volume/iso_surface.hpp"

namespace forensim {

ScalarGrid sample_phantom(const Phantom& phantom, PhantomSurface surface, double voxel_mm) {
  require_input(std::isfinite(voxel_mm) && voxel_mm > 0, "phantom '" + phantom.name() + "'", "voxel size",
                "must be positive");
  const BoundingBox box = phantom.bounds();
  const Vec3 lo = box.min - Vec3::Constant(2 * voxel_mm);
  const Vec3 extent = box.size() + Vec3::Constant(4 * voxel_mm);
  const auto count = [&](double e) { return static_cast<int>(std::ceil(e / voxel_mm)) + 1; };
  ScalarGrid grid = ScalarGrid::filled(count(extent.x()), count(extent.y()), count(extent.z()), 0.0f);
  grid.spacing = Vec3::Constant(voxel_mm);
  grid.origin = lo;
  parallel_for(
      0, static_cast<std::size_t>(grid.nz),
      [&](std::size_t k) {
        for (int j = 0; j < grid.ny; ++j) {
          for (int i = 0; i < grid.nx; ++i) {
            const Vec3 p = lo + voxel_mm * Vec3(i, j, static_cast<double>(k));
            const double d = surface == PhantomSurface::skin ? phantom.skin_distance(p) : phantom.bone_distance(p);
            grid.at(i, j, static_cast<int>(k)) = static_cast<float>(-d);
          }
        }
      },
      1);
  return grid;
}

TriMesh phantom_surface(const Phantom& phantom, PhantomSurface surface, double voxel_mm, int smoothing_iterations) {
  IsoSurfaceOptions options;
  options.smoothing_iterations = smoothing_iterations;
  return extract_iso_surface(sample_phantom(phantom, surface, voxel_mm), 0.0, options);
}

}  // namespace forensim
