#pragma once
/// Where a fitted skin and its skull intersect (Kähler, Haber and Seidel 2003, section 4.2, Figure 6a: with
/// only the user's landmarks "some skull areas still intersect the skin"): skull vertices outside the skin and
/// skin vertices inside the skull, by the generalised winding number (spatial/winding_number.hpp), which also
/// classifies points of skulls with small holes. Reported before and after interpolated landmarks.

#include <cstddef>
#include <vector>

#include "geometry/tri_mesh.hpp"

namespace forensim {

struct SkullSkinViolations {
  std::size_t skull_vertex_count = 0;
  std::size_t skin_vertex_count = 0;
  std::size_t skull_outside_skin = 0;    ///< skull vertices where the skin's winding number is below 1/2
  std::size_t skin_inside_skull = 0;     ///< skin vertices where the skull's winding number is above 1/2
  double max_skull_protrusion_mm = 0.0;  ///< largest distance of an outside skull vertex from the skin
  double max_skin_intrusion_mm = 0.0;    ///< largest distance of an inside skin vertex from the skull surface
  std::vector<std::size_t> skull_vertices_outside;  ///< their indices, ascending
  std::vector<std::size_t> skin_vertices_inside;    ///< their indices, ascending
  std::size_t total() const { return skull_outside_skin + skin_inside_skull; }
};

/// Counts the violations between `skull` and `skin` (both validated; the skin should be closed, the skull
/// closed or nearly: InputError for empty or invalid meshes). Parallel, deterministic.
SkullSkinViolations count_skull_skin_violations(const TriMesh& skull, const TriMesh& skin);

}  // namespace forensim
