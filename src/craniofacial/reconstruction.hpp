#pragma once
/// A craniofacial reconstruction as one object (Kähler, Haber and Seidel 2003, sections 3 to 4.3): skull
/// landmarks s_i (with where each came from) and a table's tissue depths give the depth vectors d_i along the
/// skull normal (skull_normals.hpp); the RBF warp of eq. 1 takes the template head's skin landmarks onto
/// q_i = s_i + d_i, with the interpolated cranium and mandible pairs (Figure 6b; fit_template.hpp); the nose
/// and mouth guides move a few skin landmarks in a second warp (section 4.3; face_guides.hpp). The result is
/// the fitted head (skin with the template's topology and UVs, muscle grids and shapes, skin-only landmarks),
/// the depth vectors, the skull and skin landmark sets, the skull/skin violations before and after the
/// interpolated landmarks, and the provenance of every landmark and depth.
///
/// The setup-once, update-many shape of the interactive case (the paper's "about an hour" is mostly a user
/// placing and moving landmarks): the skull is prepared once (closest points, patch normals), the warp is
/// factored once per landmark set and the template's points' cardinal functions are kept, so moving one
/// landmark recomputes its depth vector, re-targets the warp (O(#points) per changed pair, in parallel over
/// the skin vertices and muscle grids), re-shapes the muscles and re-applies the guides' second warp; it gives
/// the same head as a fresh reconstruction with the moved landmark. Changing the guides re-runs the second
/// warp only.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "craniofacial/face_guides.hpp"
#include "craniofacial/fit_template.hpp"
#include "craniofacial/landmark_set.hpp"
#include "craniofacial/skull_normals.hpp"
#include "craniofacial/tissue_depth_table.hpp"

namespace forensim {

struct ReconstructionOptions {
  FitTemplateOptions fit;            ///< interpolated landmarks, muscles, violation counts
  DepthVectorOptions depth;          ///< patch radius of the normals, largest landmark offset from the skull
  std::optional<FaceGuides> guides;  ///< nose and mouth guides (none: no second warp)
};

/// What a reconstruction produces. Positions in mm in the skull's frame.
struct ReconstructionResult {
  TriMesh skin;  ///< the reconstructed head: the template's skin warped (after the guides when given)
  std::vector<MuscleLayout> muscle_layouts;               ///< warped layout grids
  std::vector<MuscleShape> muscles;                       ///< shaped under `skin`
  std::vector<TemplateSkinLandmark> skin_only_landmarks;  ///< nose and mouth points of the template, warped
  DepthVectors depth_vectors;                             ///< one per bone landmark with a pair and a depth
  std::vector<bool> used_in_warp;                         ///< per depth vector: its skin landmark is the template's
  std::vector<std::string> not_on_template;               ///< bone landmarks whose skin landmark the template lacks
  LandmarkSet skull_landmarks{"skull"};                   ///< canonical names, as given (source, confidence kept)
  LandmarkSet skin_landmarks{"skin"};                     ///< q_i of the depth vectors, then the skin-only landmarks
  std::vector<std::string> guides_adjusted;               ///< landmarks the guides moved
  std::vector<Vec3> guides_adjusted_from, guides_adjusted_to;
  double guides_max_residual_mm = 0.0;          ///< of the second warp
  SkullSkinViolations violations_given_only;    ///< warp with the given pairs only
  SkullSkinViolations violations_interpolated;  ///< with the interpolated pairs
  SkullSkinViolations violations_final;         ///< of `skin` (= violations_interpolated without guides)
  bool violations_current = false;              ///< false after an update until recount_violations()
};

class Reconstruction {
 public:
  /// `head`: the template (kept by reference: it must outlive this object). `skull`: the target skull (mm,
  /// outward triangles, the same frame as the landmarks). `skull_landmarks`: any vocabulary spellings (kept
  /// under their canonical names; two spellings of one landmark are an InputError), with their source and
  /// confidence. `depths`: the table's group (select_tissue_depths, build_variants, sample_tissue_depths).
  /// Throws InputError for an invalid skull, unknown or repeated landmark names, a landmark farther than
  /// options.depth.max_surface_offset_mm from the skull, fewer than 4 landmarks on the template, degenerate
  /// landmark sets and bad guides.
  Reconstruction(const TemplateHead& head, const TriMesh& skull, const LandmarkSet& skull_landmarks,
                 const TissueDepths& depths, const ReconstructionOptions& options = {});
  ~Reconstruction();
  Reconstruction(const Reconstruction&) = delete;
  Reconstruction& operator=(const Reconstruction&) = delete;

  const ReconstructionResult& result() const { return m_result; }
  /// The fit of the first warp (pair names, sources, targets, interpolated points, residual).
  const TemplateFitResult& fit() const;
  const TemplateHead& head() const { return m_head; }
  const TriMesh& skull() const;
  const TissueDepths& depths() const { return m_depths; }
  const ReconstructionOptions& options() const { return m_options; }

  /// Moves skull landmark `name` (any spelling) to `position_mm` (its closest skull point is used) with
  /// source edited and confidence 1, or adds it when the set has none of that name; recomputes its depth
  /// vector and what depends on it (warp targets, skin, muscles, guides). Violations are left stale (call
  /// recount_violations()). Throws InputError for an unknown name, a non-finite position or one farther than
  /// options.depth.max_surface_offset_mm from the skull. Returns the number of warp targets that changed.
  std::size_t move_landmark(const std::string& name, const Vec3& position_mm);

  /// Removes skull landmark `name` (any spelling) from the set, with its depth vector and warp pair: a new
  /// landmark set, so the warp is factored anew (the template fit of eq. 1 with the remaining given pairs and
  /// the interpolated ones they generate) and the guides re-applied; the same head as a fresh reconstruction
  /// without it. A landmark outside the warp (no skin pair on the template, no depth) leaves the head as it
  /// is. Violations are left stale (call recount_violations()). Throws InputError, leaving the reconstruction
  /// unchanged, when the set has no such landmark, or when removing it would leave fewer than 4 given warp
  /// pairs or a degenerate set (all in one plane). Returns the number of warp pairs after the removal.
  std::size_t remove_landmark(const std::string& name);

  /// Replaces the tissue depths (e.g. a build variant or a sample of sample_tissue_depths) and re-targets the
  /// warp with the same factorisation: the depth vectors keep their directions and take the new lengths.
  /// Throws InputError when a landmark of the warp has no depth in `depths`. Returns the number of warp targets
  /// that changed. Violations are left stale.
  std::size_t set_depths(const TissueDepths& depths);

  /// Replaces the guides (nullopt: none) and re-runs the second warp only. Throws InputError for bad guides.
  void set_guides(const std::optional<FaceGuides>& guides);

  /// Recounts the skull/skin violations of the current head (before and after interpolated landmarks, and
  /// of the final skin).
  void recount_violations();

  /// Provenance of the landmarks and depths: {"landmarks": {"items": [one per depth vector: name,
  /// skin_landmark, source, confidence, skull_mm, direction, depth_mm, depth_source, skin_mm,
  /// surface_offset_mm, used_in_warp], missing_depth, unpaired, not_on_template, given_pairs,
  /// interpolated_pairs, max_landmark_residual_mm}, "depths": {table, group, variant, notes},
  /// "guides_adjusted": [{name, from_mm, to_mm}]}.
  nlohmann::json provenance() const;
  /// The violation counts as JSON: given_pairs_only, with_interpolated_landmarks, after_guides (with guides),
  /// each {skull_vertices, skin_vertices, skull_outside_skin, skin_inside_skull, max_skull_protrusion_mm,
  /// max_skin_intrusion_mm}; with correction rounds also before_correction (the same record, after the
  /// interpolated pairs alone, from the fit) and correction {pairs, rounds, depth}; "current": false when they
  /// predate the last update.
  nlohmann::json violations_json() const;

 private:
  void apply_guides();
  /// recount_violations(), taking the fit's own count of its skin when `fit_counted` (the fit's correction
  /// rounds end by counting it, so a fresh fit need not be counted twice).
  void count_violations(bool fit_counted);
  void assemble();

  const TemplateHead& m_head;
  TissueDepths m_depths;
  ReconstructionOptions m_options;
  SkullSurface m_surface;
  std::unique_ptr<TemplateFit> m_fit;
  ReconstructionResult m_result;
};

/// One-call form of Reconstruction.
ReconstructionResult reconstruct_face(const TemplateHead& head, const TriMesh& skull,
                                      const LandmarkSet& skull_landmarks, const TissueDepths& depths,
                                      const ReconstructionOptions& options = {});

}  // namespace forensim
