#pragma once
/// A UV-mapped open cylinder, the built-in fallback skin for painting wounds when no mesh (and no forearm-uv
/// phantom) is given, and the test mesh for continuity across a UV seam: positions are welded around the
/// circumference, but the UVs are cut along the line at angle 0 (x = radius, y = 0), which is the seam.

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Cylinder of `radius_mm` around the z axis from z = 0 to z = length_mm, `segments` around (>= 3) and
/// `rings` along (>= 1), triangles facing outward, unit vertex normals. UVs: u = arc length / s,
/// v = z / s with s = max(2 pi radius, length) (one texel density; the longer side spans [0, 1]); the seam
/// is at angle 0 (u = 0 and u = 2 pi radius / s). Throws InputError for bad sizes or counts.
TriMesh make_uv_cylinder(double radius_mm = 30.0, double length_mm = 160.0, int segments = 96, int rings = 64);

}  // namespace forensim
