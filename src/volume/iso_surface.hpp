#pragma once
/// Iso-surfaces of scalar volumes: the skin (CT ~ -500 HU) and bone (~ +150..400 HU) surfaces of a head scan as
/// closed triangle meshes.

#include "geometry/tri_mesh.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

struct IsoSurfaceOptions {
  int keep_largest_components = 0;  ///< keep only this many components of largest area (0 = keep all)
  int smoothing_iterations = 0;     ///< Taubin lambda|mu iteration pairs after extraction (0 = none)
  double smoothing_lambda = 0.5;    ///< Taubin lambda (> 0)
  double smoothing_mu = -0.53;      ///< Taubin mu (< -lambda)
  double resample_factor = 1.0;     ///< > 1 extracts from a grid that many times coarser (faster, fewer triangles)
};

/// Extracts the surface where `grid` crosses `iso_value` as a closed, welded, outward-oriented triangle mesh in world
/// (LPS) mm: values above the iso-value are inside, triangles are counter-clockwise seen from outside. The volume is
/// padded with a background below the iso-value, so objects touching the volume's border are closed there.
/// Uses OpenVDB's tools::volumeToMesh (uniform, adaptivity 0) on a grid built from the dense samples, its quads split
/// along the shorter diagonal. Samples exactly at the iso-value count as outside (nudged by 1e-4 of the value range),
/// which keeps zero-area triangles out of integer CT data. Vertex normals are filled. Throws InputError for an invalid
/// grid or non-finite iso-value; returns an empty mesh when no sample is above the iso-value.
TriMesh extract_iso_surface(const ScalarGrid& grid, double iso_value, const IsoSurfaceOptions& options = {});

}  // namespace forensim
