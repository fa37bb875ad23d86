#pragma once
/// A procedural CT of the `head` phantom (head_phantom.hpp): the built-in default volume, so every volume command and
/// the demo work with no data. Values follow the convention of CT data stored as HU + 1024 (air about 0, soft tissue
/// about 1000, bone 1500 to 2200), so the iso-values that suit real scans (skin 500, bone 1150) suit it too. Axes are
/// LPS millimetres: x to the patient's left, y posterior, z superior; the face looks toward -y.

#include <cstdint>

#include "volume/scalar_grid.hpp"

namespace forensim {

struct CtHeadPhantomOptions {
  double voxel_mm = 2.0;   ///< isotropic spacing
  double noise_hu = 20.0;  ///< standard deviation of deterministic acquisition noise
  std::uint64_t seed = 1;  ///< noise seed
};

/// Iso-values that separate air from skin and soft tissue from bone in the phantom (and in HU+1024 data).
inline constexpr double ct_phantom_skin_iso = 500.0;
inline constexpr double ct_phantom_bone_iso = 1150.0;

/// Signed distance (mm, negative inside) to the head phantom's skin and to its bone, at a world position.
double ct_phantom_skin_distance(const Vec3& p);
double ct_phantom_bone_distance(const Vec3& p);

/// Samples the phantom on a grid that encloses the head and neck with a margin of air.
ScalarGrid make_ct_head_phantom(const CtHeadPhantomOptions& options = {});

}  // namespace forensim
