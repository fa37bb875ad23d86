#pragma once
/// The reconstruction's fitting stage on plain data (Kähler, Haber and Seidel 2003, section 4.2): skull
/// landmarks s_i with depth vectors d_i give target skin points q_i = s_i + d_i; the RBF warp of eq. 1 that
/// takes the template's skin landmarks p_i onto them is applied to the template's skin vertices and to its
/// muscle layout grids (the mesh's topology, UVs and textures are kept: only positions move), then the muscle
/// shapes are recomputed under the warped skin. Interpolated landmark pairs on the cranium and mandible
/// (interpolated_landmarks.hpp, Figure 6b) are added to the given ones, and the skull/skin violations are
/// reported for the warp with the given pairs only and for the final one. Where the skull still pierces the
/// skin (or the skin enters the skull) after them, correction pairs are added at the violations and the warp
/// solved again, round after round until none remain (violation_correction.hpp).
///
/// TemplateFit keeps the factorised warp and, from the first landmark move on, the cardinal functions of the
/// template's points, so moving one landmark (the interactive case) re-targets the warp and moves the head in
/// O(#points) per changed pair.

#include <memory>
#include <string>
#include <vector>

#include "craniofacial/interpolated_landmarks.hpp"
#include "craniofacial/muscle_layout.hpp"
#include "craniofacial/skull_skin_violations.hpp"
#include "craniofacial/template_head.hpp"
#include "craniofacial/violation_correction.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

class RayCaster;
class RbfWarp;
class RbfPointWarp;

struct FitTemplateOptions {
  bool interpolated_landmarks = true;
  LandmarkInterpolationOptions interpolation;
  bool muscles = true;           ///< warp the muscle grids and reshape them under the skin
  bool count_violations = true;  ///< skull/skin violations before and after interpolated landmarks
  /// Correction pairs at the violations left by the warp (rounds 0: none). Needs no counting option: the
  /// rounds count the violations themselves.
  ViolationCorrectionOptions correction;
};

struct TemplateFitResult {
  TriMesh skin;  ///< the template's skin (same triangles, UVs, material) at the warped positions, new normals
  std::vector<MuscleLayout> muscle_layouts;          ///< warped layout grids
  std::vector<MuscleShape> muscles;                  ///< shaped under the warped skin
  std::vector<TemplateSkinLandmark> skin_landmarks;  ///< the template's skin-only landmarks, warped
  /// Landmark pairs of the warp: the given ones (their template skin names) first, then the interpolated ones,
  /// then the correction pairs ("correction_<k>").
  std::vector<std::string> pair_names;
  std::vector<Vec3> sources;  ///< template skin points p_i
  std::vector<Vec3> targets;  ///< q_i = s_i + d_i on the target
  std::size_t given_pair_count = 0;
  InterpolatedLandmarks interpolated;    ///< on the target skull (only those also found on the template's)
  ViolationCorrectionPairs corrections;  ///< the correction pairs, in the order added
  int correction_rounds = 0;             ///< rounds that added pairs
  /// After the given and interpolated pairs, before any correction (counted when corrections ran or
  /// count_violations is set).
  SkullSkinViolations violations_before_correction;
  SkullSkinViolations violations_given_only;  ///< after the warp with the given pairs only
  SkullSkinViolations violations;             ///< after the final warp
  double max_landmark_residual_mm = 0.0;      ///< max |f(p_i) - q_i| of the final warp
  double seconds_setup = 0.0;                 ///< factorisation and cardinal functions
  double seconds_total = 0.0;
};

class TemplateFit {
 public:
  /// `head`: the template (kept by reference: it must outlive the fit). `skull`: the target skull (mm, the
  /// head's frame). `landmarks`: names (a template pair's skin name, or its bone name when that is unique),
  /// skull positions and depth vectors. Throws InputError for an unknown or repeated name, sizes that differ,
  /// fewer than 4 usable pairs, non-finite values, or degenerate landmark sets (RbfWarp).
  /// `counter`: a violation counter of this same skull to share (a new fit of the skull keeps its trees and
  /// remembered skin); null: the fit makes its own.
  TemplateFit(const TemplateHead& head, const TriMesh& skull, const LandmarkDepths& landmarks,
              const FitTemplateOptions& options = {}, std::shared_ptr<SkullSkinViolationCounter> counter = nullptr);
  ~TemplateFit();
  TemplateFit(const TemplateFit&) = delete;
  TemplateFit& operator=(const TemplateFit&) = delete;

  const TemplateFitResult& result() const { return m_result; }

  /// Moves the given landmark `name` (as in the constructor) to a new skull position and depth vector, and
  /// updates the interpolated targets that depend on it, the skin and the muscles: the same result as a fresh
  /// fit with the moved landmark. While the pair set stays the same the factorisation and the cardinal functions
  /// are reused (O(#points) per changed target); when an interpolated point appears or vanishes on the target
  /// the new pair set is factored anew. Violations are not recounted (call recount_violations()). Returns the
  /// number of warp targets that changed (all of them after a new factorisation). The correction pairs are kept,
  /// their depths re-read from their neighbouring landmarks (call correct_violations() for violations the move
  /// made: "the same result as a fresh fit" holds for the same pair set).
  std::size_t move_landmark(const std::string& name, const Vec3& skull_position, const Vec3& depth_vector);
  /// All given landmarks at once (the constructor's order and names; e.g. new tissue depths): as
  /// move_landmark, one re-targeting of the warp. Throws InputError for sizes that differ from the fit's
  /// landmark count or non-finite values. Returns the number of warp targets that changed.
  std::size_t set_landmarks(const std::vector<Vec3>& skull_positions, const std::vector<Vec3>& depth_vectors);
  /// Recounts result().violations for the current skin.
  void recount_violations();
  /// The violations between the skull and `skin` (the template's skin at other positions, such as the guided
  /// skin), by the fit's counter: equal to count_skull_skin_violations(skull, skin), faster after the fit's own
  /// counts of nearby skins.
  SkullSkinViolations count_violations(const TriMesh& skin);
  /// The counter (to share with a new fit of the same skull).
  const std::shared_ptr<SkullSkinViolationCounter>& violation_counter() const { return m_counter; }
  /// Runs the correction rounds again for the current landmarks (options.correction; the constructor runs them
  /// once): the pairs found so far are kept, new ones are added where violations remain. Updates
  /// result().violations. Returns the number of pairs added.
  std::size_t correct_violations();

 private:
  /// The interpolated points on the target for the current given landmarks (none without interpolation).
  InterpolatedLandmarks target_interpolation() const;
  /// The template's interpolated points that `s` also holds, in the template's order.
  std::vector<std::string> kept_interpolated_names(const InterpolatedLandmarks& s) const;
  /// Builds the pair set from the given landmarks, `s` and the correction pairs, factors the warp and warps
  /// every point (the muscles shaped under the new skin unless `shape_muscles_now` is false).
  void factor(const InterpolatedLandmarks& s, bool count_violations, bool shape_muscles_now = true);
  /// The cardinal functions of the points for the current pair set, made on first use after a factorisation.
  const RbfPointWarp& point_warp();
  /// Targets of the correction pairs from the current given depth vectors.
  void update_correction_depths();
  /// Skin, skin-only landmarks and muscle grids from m_warped; the muscles shaped under the skin when
  /// `shape_muscles_now`.
  void apply_positions(bool shape_muscles_now = true);
  /// Targets from the current given landmarks; skin and muscles updated (refactored if the pair set changed).
  /// `regenerate` (k_cranium, k_mandible or both): the interpolated generators run again on the target; the
  /// others' points are kept (the moved landmarks do not feed them).
  std::size_t retarget(int regenerate);
  /// Targets from the given landmarks and the interpolated points `s` (holding every kept name).
  std::size_t retarget_with(const InterpolatedLandmarks& s);
  /// The generators of interpolate_landmarks that read the bone landmark `bone_name`: k_cranium (frame and
  /// breadth), k_mandible (an arc's end), both or 0.
  int feeds_interpolation(const std::string& bone_name) const;
  static constexpr int k_cranium = 1, k_mandible = 2;

  const TemplateHead& m_head;
  TriMesh m_skull;
  FitTemplateOptions m_options;
  std::unique_ptr<RayCaster> m_skull_rays;
  std::shared_ptr<SkullSkinViolationCounter> m_counter;
  LandmarkDepths m_given;  ///< the input, keyed by bone names for the interpolation
  std::vector<std::string> m_input_names;
  std::vector<std::string> m_template_interpolated_names;  ///< generated on the template's skull
  std::vector<Vec3> m_template_interpolated_skin;          ///< their skin points on the template (sources)
  std::vector<std::string> m_interpolated_names;           ///< the pairs kept (found on both skulls)
  std::vector<Vec3> m_points;                              ///< skin vertices, skin-only landmarks, muscle grids
  std::unique_ptr<RbfWarp> m_warp;
  std::unique_ptr<RbfPointWarp> m_point_warp;  ///< cardinal functions at m_points (null until needed)
  std::vector<Vec3> m_warped;
  TemplateFitResult m_result;
};

/// One-call form of TemplateFit.
TemplateFitResult fit_template(const TemplateHead& head, const TriMesh& skull, const LandmarkDepths& landmarks,
                               const FitTemplateOptions& options = {});

}  // namespace forensim
