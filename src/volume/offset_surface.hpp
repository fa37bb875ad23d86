#pragma once
/// Inner offset surfaces: the surface a given depth inside a closed skin, as a closed mesh. A scanned body part
/// has a skin and no bones, but the desiccation model (Frerichs, Vidler and Gatzidis 2020, section 4) needs a
/// bone region whose nodes stay fixed; the skin offset inwards by a typical soft-tissue depth stands in for it
/// (an approximate bone that keeps that depth of flesh everywhere under the skin).

#include "geometry/tri_mesh.hpp"

namespace forensim {

struct InnerOffsetOptions {
  double depth_mm = 8.0;            ///< distance of the offset surface below the skin, mm (> 0)
  double voxel_mm = 0.0;            ///< level-set voxel size, mm (0: depth / 2, clamped to [0.5, 3])
  int keep_largest_components = 1;  ///< keep this many components of largest area (0 = keep all)
  int smoothing_iterations = 4;     ///< Taubin lambda|mu iteration pairs on the offset surface (0 = none)
};

/// The surface at `options.depth_mm` inside `skin` (mm): the level set -depth of the skin's signed distance
/// field, built and meshed by OpenVDB (tools::meshToSignedDistanceField with an interior band wider than the depth,
/// then tools::volumeToMesh at that iso-value). The result is closed and outward-oriented, in the skin's frame.
/// The skin must be closed (check_topology: InputError naming `source` otherwise) and finite. Parts of the body
/// thinner than twice the depth (fingers, ears, the nose) have no offset surface inside them. Throws InputError
/// naming `source` for a depth or voxel size out of range, and when no part of the skin is thicker than twice the
/// depth (the offset surface would be empty).
TriMesh inner_offset_surface(const TriMesh& skin, const InnerOffsetOptions& options = {},
                             const std::string& source = "skin");

}  // namespace forensim
