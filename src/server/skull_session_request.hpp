#pragma once
/// The request bodies of the skull editor's endpoints (skull_sessions.hpp), read through the job loader
/// (core/job.hpp), so a key nobody reads is an error naming it and every bad value answers 400 with the JSON
/// pointer of its field. Paths in requests are relative to the served folder and resolved through
/// served_path.hpp (".." and absolute paths are refused, 400; a symbolic link out of the folder 403; a missing
/// file 404).

#include <filesystem>
#include <optional>
#include <string>

#include "core/job.hpp"
#include "core/types.hpp"
#include "craniofacial/face_guides.hpp"

namespace forensim {

/// Which tissue depths: a table (built-in name or a CSV file) and its group.
struct SkullDepthChoice {
  std::string table = "ttable_2023";        ///< "ttable_2023", "rhine_1983" or a resolved CSV path
  std::string table_label = "ttable_2023";  ///< as the request named it
  std::string sex;                          ///< "", female, male or pooled
  std::string build;                        ///< "" (the group's own values), slender, normal or obese
};

/// POST /api/skull/sessions:
///   {"skull": "builtin" | "PATH" (a mesh file or a CT volume in the served folder), "unit": "auto" (a mesh's
///    units: auto, m, cm, mm, in), "landmarks": "auto" (detected, with confidences) | "template" (the built-in
///    skull's own) | "PATH.mrk.json" | "PATH.csv", "table", "sex", "build" (as SkullDepthChoice),
///    "template_detail": "full" | "coarse", "interpolated_landmarks": true, "guides": {FaceGuides fields}}
struct SkullSessionRequest {
  std::string skull = "builtin";  ///< "builtin" or a resolved path
  std::string skull_label = "builtin";
  std::string unit = "auto";
  std::string landmarks = "auto";  ///< "auto", "template" or a resolved path
  std::string landmarks_label = "auto";
  SkullDepthChoice depths;
  std::string template_detail = "full";
  bool interpolated_landmarks = true;
  std::optional<FaceGuides> guides;
};

/// POST /api/skull/sessions/ID/landmarks: {"name": "zy_L", "position": [x, y, z]} (LPS mm on the skull).
struct LandmarkEdit {
  std::string name;
  Vec3 position_mm = Vec3::Zero();
};

/// Largest coordinate accepted in a position, mm (a skull is about 200 mm across).
constexpr double kMaxCoordinateMm = 1e5;

/// Parses `text` as a JSON object (`what` names it in messages). Throws ApiError 400 for bad JSON or a body
/// that is not an object.
JobDocument parse_request(const std::string& text, const std::string& what);

SkullSessionRequest read_skull_session_request(const JobNode& root, const std::filesystem::path& served_root);
/// {"name", "position"}: the name must be non-empty (whether it is a known landmark is the session's to say);
/// the position three finite numbers within kMaxCoordinateMm.
LandmarkEdit read_landmark_edit(const JobNode& root);
/// POST /api/skull/sessions/ID/depths: {"table", "sex", "build"} (each defaulting as in the session request).
SkullDepthChoice read_depth_choice(const JobNode& root, const std::filesystem::path& served_root);
/// POST /api/skull/sessions/ID/guides: {"guides": {FaceGuides fields} | null}; nullopt for null, no values or
/// no "guides" key (the second warp is then left out).
std::optional<FaceGuides> read_guides_request(const JobNode& root);

}  // namespace forensim
