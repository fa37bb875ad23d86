#pragma once
/// A partial skull completed with the registered reference skull where the scan saw nothing (issue 8: a CT
/// cut off above the orbits has no vault, yet the reconstruction needs the vault's landmarks, the interpolated
/// cranium pairs and the skull under the forehead's skin). The scanned part is kept as it is, less the caps
/// that close it at the lattice's faces (scan_field_of_view.hpp); the reference skull, mapped by the
/// registration (similarity and non-rigid field: skull_registration.hpp), supplies every triangle that lies
/// wholly outside the field of view. The two parts meet at the cut without being stitched: the result is an
/// open mesh, outward oriented, whose closest points and normals are those of the scan inside the view and of
/// the registered reference outside it: a fragmentary skull completed from a reference skull fitted to what
/// remains.

#include <cstddef>

#include "craniofacial/scan_field_of_view.hpp"
#include "craniofacial/skull_registration.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

struct SkullCompletion {
  TriMesh mesh;                         ///< the completed skull, mm
  std::size_t scan_triangles = 0;       ///< triangles kept from the scan
  std::size_t cap_triangles = 0;        ///< scan triangles dropped as caps
  std::size_t reference_triangles = 0;  ///< triangles added from the registered reference
};

/// Completes `scan` (mm, outward) seen through `view` with `reference` mapped by `registration` (reference ->
/// scan). With an unbounded view the scan is returned unchanged. Throws InputError naming "scan skull" or
/// "reference skull" for a mesh without triangles.
SkullCompletion complete_skull(const TriMesh& scan, const ScanFieldOfView& view, const TriMesh& reference,
                               const SkullRegistration& registration);

}  // namespace forensim
