#pragma once
/// Surface meshes of phantoms: the signed distance sampled on a grid, then iso-surfaced at zero (closed,
/// outward-oriented, welded triangle meshes in mm).

#include "geometry/tri_mesh.hpp"
#include "phantoms/phantom.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

enum class PhantomSurface { skin, bone };

/// The negated signed distance (mm, positive inside) to a phantom's skin or bone on a grid of `voxel_mm`
/// spacing covering phantom.bounds() plus two voxels. Parallel; deterministic.
ScalarGrid sample_phantom(const Phantom& phantom, PhantomSurface surface, double voxel_mm);

/// The zero iso-surface of sample_phantom(), with `smoothing_iterations` Taubin steps. Throws InputError for a
/// non-positive voxel size or one so small the grid would exceed the volume module's limits.
TriMesh phantom_surface(const Phantom& phantom, PhantomSurface surface, double voxel_mm, int smoothing_iterations = 0);

}  // namespace forensim
