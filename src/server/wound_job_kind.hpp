#pragma once
/// The "wound" job kind of `forensim serve`: a wound timeline painted on a built-in mesh or on a mesh file in
/// the served folder, validated with the wound job loader (wound/wound_job.hpp) and run by `forensim wound`.
///
/// Request (beside "kind": "wound" and "output"):
///   "mesh": "forearm-uv" | "cylinder" | a mesh file relative to the served folder (default "forearm-uv"),
///   "unit": the mesh file's unit ("auto", "m", "cm", "mm", "in"),
///   "resolution": texels per side (32..4096, default 512), "seed" (default 1),
///   "times": times after injury to write ("1h,36h,5d", default "1h,36h,5d,3w"; "" for none),
///   "picture_size": pixels of the close-up renders (0..1024, default 0: none),
///   "job": the wound job file (strokes as surface points in mm or UV points, type, shape, keys); without it
///          the CLI's default stroke.

#include <memory>

#include "server/builtin_meshes.hpp"
#include "server/job_manager.hpp"

namespace forensim {

JobKind wound_job_kind(std::shared_ptr<BuiltinMeshes> meshes);

}  // namespace forensim
