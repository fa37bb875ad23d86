#pragma once
/// One editing session of `forensim serve`'s skull editor: a skull (built-in, a mesh or a CT of the served
/// folder), its landmarks (detected with a confidence each, the template's own, or from a file), a tissue-depth
/// table's group and the reconstructed face, kept in memory as a Reconstruction (craniofacial/reconstruction.hpp)
/// so that moving one landmark re-targets the factored warp instead of reconstructing anew (Kähler, Haber and
/// Seidel 2003: the user places and moves landmarks, section 3; the guides of section 4.3; expressions by muscle
/// contraction, section 5). Every operation takes the session's mutex, so concurrent requests on one session
/// are served one after the other; answers are JSON (positions in LPS mm, the skull's frame; meshes as
/// mesh_arrays.hpp encodes them).

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "craniofacial/face_expression.hpp"
#include "craniofacial/reconstruction.hpp"
#include "craniofacial/skull_input.hpp"
#include "craniofacial/skull_skin_violations.hpp"
#include "craniofacial/template_head.hpp"
#include "server/skull_session_request.hpp"

namespace forensim {

class SkullSession {
 public:
  /// Loads the skull, places its landmarks and reconstructs the face. Throws ApiError 400 naming the request
  /// field at fault (the skull, landmark file or table that cannot be read or used).
  SkullSession(std::string id, std::shared_ptr<const TemplateHead> head, const SkullSessionRequest& request);
  ~SkullSession();
  SkullSession(const SkullSession&) = delete;
  SkullSession& operator=(const SkullSession&) = delete;

  const std::string& id() const { return m_id; }

  /// The whole state: {"id", "skull": {source, kind, triangles, notes}, "template_detail", "landmarks": [...],
  /// "addable": [...], "depths": {...}, "guides", "guide_values", "expressions": [preset names],
  /// "face": mesh arrays, "skull_mesh": mesh arrays (when `geometry`), "timings_ms", "provenance"}.
  /// A landmark: {name, full_name, position_mm, source, confidence, skin_landmark, skin_mm, depth_mm,
  /// used_in_warp} (the last four when it has a depth vector).
  nlohmann::json describe(bool geometry);
  /// Moves landmark `edit.name` (any vocabulary spelling) to the closest skull point of `edit.position_mm`, or
  /// adds it when the set has none of that name: {"landmark", "added", "landmarks", "addable", "face":
  /// {"positions_f32"}, "changed_targets", "update_ms" (the reconstruction's update), "encode_ms"}.
  /// Throws ApiError 400 with field "/name" for a name that is not a bone landmark of the vocabulary and
  /// "/position" for a position too far from the skull; the session is then unchanged.
  nlohmann::json move_landmark(const LandmarkEdit& edit);
  /// Removes landmark `name` (any vocabulary spelling) with its depth vector and warp pair
  /// (Reconstruction::remove_landmark): {"removed", "warp_pairs", "landmarks", "addable", "face":
  /// {"positions_f32"}, "update_ms", "encode_ms"}. Throws ApiError 404 (field "name") when the set has no such
  /// landmark and 400 (field "name") when removing it would leave fewer than 4 given warp pairs or a degenerate
  /// set; the session is then unchanged.
  nlohmann::json remove_landmark(const std::string& name);
  /// The skull/skin violations of the current face (count_skull_skin_violations of the final skin, after the
  /// guides; kept until the face changes): {"skull_through_skin" (skull vertices outside the skin),
  /// "skin_inside_skull" (skin vertices inside the skull), "max_skull_protrusion_mm", "max_skin_intrusion_mm",
  /// "face_version", "recounted", "count_ms"}. A count takes longer than an update (seconds on the full
  /// template), so it runs on a copy of the face without holding the session: edits meanwhile are served at
  /// once, and a count that an edit overtook is answered for the face it counted (face_version) but not kept.
  /// With `all`, Reconstruction::recount_violations (the warp with the given pairs only, with the interpolated
  /// pairs, after the guides) holding the session, and "counts": Reconstruction::violations_json().
  nlohmann::json violations(bool all);
  /// Replaces the tissue depths (table, sex, build): {"depths", "landmarks", "face", "update_ms", ...}.
  nlohmann::json set_depths(const SkullDepthChoice& choice);
  /// Replaces the guides (nullopt: none): {"guides", "guide_values", "guides_adjusted", "face", "update_ms"}.
  nlohmann::json set_guides(const std::optional<FaceGuides>& guides);
  /// A preset expression of the current face (expression_preset_names()): {"name", "positions_f32", "seconds",
  /// "cached", "max_displacement_mm"}. Poses are kept until the face changes. ApiError 400 "/name" for an
  /// unknown preset.
  nlohmann::json expression(const std::string& name);
  /// The skull ("skull") or skin ("skin") landmarks as Slicer markups JSON text (.mrk.json).
  std::string markups(const std::string& which);
  /// The head (with the named expressions as morph targets) and the skull as GLB bytes.
  std::string glb(const std::vector<std::string>& expressions);
  /// Writes a run folder as `forensim reconstruct` does (head.glb, skull and skin .mrk.json, provenance.json,
  /// run.json) at `folder`, which must not exist. Returns the files written.
  nlohmann::json save(const std::filesystem::path& folder, const std::vector<std::string>& expressions);

  /// Seconds since the last request touched the session.
  double idle_seconds() const;
  /// {"id", "skull", "landmarks", "idle_s"}.
  nlohmann::json summary() const;

 private:
  void touch();
  nlohmann::json landmarks_json() const;
  nlohmann::json addable_json() const;
  nlohmann::json depths_json() const;
  nlohmann::json guide_values_json() const;
  nlohmann::json face_positions_json() const;
  void changed();
  const FaceExpressions& expressions_model();
  std::vector<MorphTarget> morph_targets(const std::vector<std::string>& expressions);
  nlohmann::json record() const;

  std::string m_id;
  std::shared_ptr<const TemplateHead> m_head;
  /// The template carried onto the skull by the registration of detected landmarks (null: m_head is fitted).
  std::shared_ptr<const TemplateHead> m_fitted_head;
  SkullSessionRequest m_request;
  Skull m_skull;
  std::string m_landmark_origin;
  nlohmann::json m_detection = nullptr;  ///< registration figures when the landmarks were detected
  SkullDepthChoice m_depth_choice;
  std::unique_ptr<Reconstruction> m_reconstruction;
  std::unique_ptr<FaceExpressions> m_expressions;    ///< of the current face (built on first use)
  std::map<std::string, std::vector<Vec3>> m_poses;  ///< expressions of the current face
  std::uint64_t m_face_version = 0;                  ///< counts the changes of the face
  std::optional<SkullSkinViolations> m_violations;   ///< of the face at m_violations_version
  std::uint64_t m_violations_version = 0;
  /// Counts the violations off m_mutex (a count after an edit re-evaluates only the skull vertices the skin can
  /// have swept past); built on first use, guarded by m_counter_mutex.
  std::unique_ptr<SkullSkinViolationCounter> m_counter;
  std::mutex m_counter_mutex;
  nlohmann::json m_timings_ms = nlohmann::json::object();
  std::atomic<std::int64_t> m_last_used_ns{0};
  mutable std::mutex m_mutex;
};

/// The depths of a choice (a table's group, or its build variant) as `forensim reconstruct` selects them.
/// Throws InputError / IoError from the table.
TissueDepths select_session_depths(const SkullDepthChoice& choice);

}  // namespace forensim
