#pragma once
/// A desiccation frame (one .vtu of a mummify run's .pvd series) as the browser draws it: the outer surface
/// of the tet volume with the per-node fields sampled at its vertices, in a compact JSON object.

#include <nlohmann/json.hpp>

#include <filesystem>

namespace forensim {

/// Reads the tetrahedral .vtu at `vtu_path` and returns its boundary surface:
///   {"vertex_count": #S, "triangle_count": #F,
///    "positions": [3 #S] current node positions, mm (rounded to 1 um),
///    "rest_positions": [3 #S] positions minus the "displacement" field (when present), mm,
///    "triangles": [3 #F] vertex indices, counter-clockwise seen from outside,
///    "scalars": {name: [#S]} every per-node scalar field (moisture, water_percent, ...),
///    "ranges": {name: [min, max]} over the surface}
/// Throws what read_vtu throws (InputError for malformed files, IoError when unreadable).
nlohmann::json frame_surface_json(const std::filesystem::path& vtu_path);

}  // namespace forensim
