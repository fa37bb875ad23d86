#pragma once
/// Body model folders: how a body model (tet volume, skin, tracking connections, parts) is stored between
/// `forensim tetrahedralize --model` and the simulations that read it. A folder holds
///   model.json  format name and version, units (mm), file names, part names, counts, and the pose ("pose":
///               {"views": "arm"|"head", "up", "front", "gravity": [x, y, z]}; absent: BodyPose's defaults)
///   volume.vtu  the tets: cell arrays "label" (TissueLabel) and "part" (index into the part names)
///   skin.vtu    the skin triangles with point arrays "Normals", "part" and the tracking connections:
///               "tracking_face" (boundary face index), "tracking_nodes" (3 node indices), "tracking_weights"
///               (3 barycentric weights), "tracking_rest_distance" (mm), "tracking_side" (-1 inside, +1
///               outside), "tracking_method" (TrackingMethod)
/// All numbers are stored as Float64 (indices are exact below 2^53), so a folder reads back bit for bit, and
/// ParaView opens both meshes with every array.

#include <filesystem>
#include <string>

#include "body/body_model.hpp"

namespace forensim {

/// Writes `model` into `folder` (created if missing). Files are written atomically; model.json last, so a
/// folder without it is incomplete. Throws InputError for an invalid model, IoError when writing fails.
void write_body_model(const std::filesystem::path& folder, const BodyModel& model);

/// Reads a folder written by write_body_model and validates it (BodyModel::validate: the boundary faces are
/// recomputed and every tracking connection checked against them). Throws InputError naming the file and the
/// problem (missing or unknown format/version, count mismatches, bad indices), IoError when a file is missing.
BodyModel read_body_model(const std::filesystem::path& folder);

}  // namespace forensim
