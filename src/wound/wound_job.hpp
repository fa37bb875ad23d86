#pragma once
/// The wound job file: the plain JSON a `forensim wound` run, the server and the tests load through
/// core/job.hpp (unknown keys are errors naming the key). Version 1:
///
///   {
///     "version": 1,
///     "type": "abrasion",                  // or "bruise"
///     "shape": "strokes",                  // or "convex_hull" (the thesis's hull of the stroke points)
///     "distance": "surface",               // or "uv" (the thesis's way, for comparison)
///     "strokes": [
///       {"points": [[x, y, z], ...], "radius_mm": 3},   // surface points, mm
///       {"uv": [[u, v], ...], "radius_mm": 2},           // or UV points (u right, v up)
///       {"screen": [[x, y], ...], "radius_mm": 3,         // or pixels drawn over a view of the mesh
///        "camera": {"view": "front", "axes": "lps", "width": 1024, "height": 1024, "fov_deg": 30}}
///        // (a named view framed on the mesh; axes "lps" or "y_up"; or "eye", "target", "up" in mm)
///     ],
///     "abrasion": {"thesis_texels_per_mm": 8, "scab_height_mm": 0.8, "skin_reflection": 0.25,
///                  "glow_thickness_px": 100, "scab_gradient_px": 100, "thesis_closing_distance": false},
///     "keys": [ {"phase": "vasoconstriction", "time": "0s", "label": "...", "position": 0}, ... ]
///   }
///
/// Without "keys" the wound type's default timeline is used; with them, each key names a phase of the type
/// (abrasion phases, or bruise stages) at a time ("36h", "5d"); entries of the same phase and position
/// share one key position (a hold), so the timeline's hold pairs and instant cuts are written plainly.
/// Screen strokes are recorded as the thesis does (chapter 4.2.1, eqs. 4.1 to 4.3; wound/screen_stroke.hpp):
/// a ray from the camera through each pixel, the first hit kept, pixels off the mesh skipped.

#include <optional>
#include <string>
#include <vector>

#include "core/job.hpp"
#include "geometry/tri_mesh.hpp"
#include "wound/abrasion.hpp"
#include "wound/timeline.hpp"
#include "wound/wound_canvas.hpp"

namespace forensim {

struct WoundJob {
  std::string type = "abrasion";
  std::vector<WoundStroke> strokes;
  CanvasOptions canvas;
  AbrasionParams abrasion;
  std::vector<TimelineEntry> timeline;
};

/// Reads a wound job from `root` for painting on `mesh_with_uvs`; `type_override` (from the command line)
/// wins over the job's "type". Converts UV strokes to surface points. Throws JobError for bad keys and
/// values, InputError for UV points outside every UV triangle. Does not call check_all_used().
WoundJob read_wound_job(const JobNode& root, const TriMesh& mesh_with_uvs,
                        const std::optional<std::string>& type_override = std::nullopt);

/// The surface point (mm) whose UV is `uv`: the first UV triangle containing it, by barycentric weights.
/// std::nullopt when no UV triangle contains it.
std::optional<Vec3> surface_point_at_uv(const TriMesh& mesh_with_uvs, const Vec2& uv);

}  // namespace forensim
