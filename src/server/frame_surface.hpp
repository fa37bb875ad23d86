#pragma once
/// A frame of a run as the browser draws it: one .vtu of a mummify run's series (a tetrahedral volume frame
/// of desiccation.pvd, drawn as its outer surface, or a triangle skin frame of skin.pvd) or any other triangle
/// .vtu a run writes (a reconstructed skin with an "uncertainty" field), with its per-vertex fields, in a
/// compact JSON object.

#include <nlohmann/json.hpp>

#include <filesystem>

namespace forensim {

/// Reads the .vtu at `vtu_path`, of tetrahedra (VTK_TETRA) or triangles (VTK_TRIANGLE), and returns its surface
/// (the boundary of a tet volume; a triangle mesh as it is):
///   {"vertex_count": #S, "triangle_count": #F, "cells": "tetrahedra" | "triangles",
///    "positions": [3 #S] current vertex positions, mm (rounded to 1 um),
///    "rest_positions": [3 #S] positions minus the "displacement" vector field, mm (only when the frame has one),
///    "triangles": [3 #F] vertex indices, counter-clockwise seen from outside,
///    "scalars": {name: [#S]} every per-vertex scalar field (moisture, water_percent, uncertainty, ...),
///    "ranges": {name: [min, max]} of each scalar field over the surface,
///    "vectors": {name: [3 #S]} every per-vertex 3-vector field but "displacement" (a skin frame's linear RGB
///               "colour")}
/// Throws InputError for a malformed file or one of other cells (naming the file and what is wrong), IoError when
/// it cannot be read.
nlohmann::json frame_surface_json(const std::filesystem::path& vtu_path);

}  // namespace forensim
