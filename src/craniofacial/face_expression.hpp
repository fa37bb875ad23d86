#pragma once
/// Facial expressions of a reconstructed (or the template) head by muscle contraction (Kähler, Haber and
/// Seidel 2003, section 5 and Figure 8): named presets (neutral, smile, frown, worried, surprise) and free
/// activations by muscle name drive the skin-muscle-skull model (skin_muscle_model.hpp,
/// muscle_contraction.hpp) to a static equilibrium; the result is the displaced skin, ready to be written
/// as glTF morph targets (mesh_io/gltf_writer.hpp).

#include <map>
#include <string>
#include <vector>

#include "craniofacial/fit_template.hpp"
#include "craniofacial/muscle_contraction.hpp"
#include "craniofacial/skin_muscle_model.hpp"
#include "mesh_io/gltf_writer.hpp"

namespace forensim {

/// Activations by name, each in [0, 1]. A name is a muscle's ("zygomaticus_major_L") or a bilateral muscle's
/// without its side suffix ("zygomaticus_major": both sides).
using MuscleActivations = std::map<std::string, double>;

/// Names of the presets: "neutral", "smile", "frown", "worried", "surprise".
std::vector<std::string> expression_preset_names();

/// Preset names from a comma-separated list as users write them ("smile,frown"; "none": no expressions),
/// in the order given, each once. Throws InputError(source, text, ...) for an empty name; the names are not
/// checked against the presets (expression_preset() does, naming the closest one).
std::vector<std::string> parse_expression_list(const std::string& text, const std::string& source = "expressions");

/// A preset's activations (by bilateral names). Throws InputError for an unknown preset, with the closest
/// name ("did you mean ...").
MuscleActivations expression_preset(const std::string& name);

/// One activation per muscle of `muscle_names` (in that order, unnamed ones 0) from `activations`. Throws
/// InputError naming the entry for an unknown muscle (with the closest name, "did you mean ...") or a value
/// outside [0, 1] or NaN.
std::vector<double> resolve_activations(const std::vector<std::string>& muscle_names,
                                        const MuscleActivations& activations);

/// An expression: the skin's vertex positions at equilibrium.
struct FaceExpression {
  std::string name;
  std::vector<Vec3> skin_positions;  ///< #V, mm, same order as the neutral skin
  int newton_iterations = 0;         ///< iterations of the contraction solver (quasi-Newton by default)
  double seconds = 0.0;
};

/// The expression system of one head: builds the spring model and its solver once, then poses it.
class FaceExpressions {
 public:
  /// `skin`: the head's skin (the template's or a fit's); `skull`: its skull (the target skull after a fit);
  /// `muscles`: shaped under `skin` (TemplateFitResult::muscles, or shape_muscles(head.muscles, head.skin)).
  /// Throws InputError as make_skin_muscle_model() and MuscleContractionSolver do.
  FaceExpressions(const TriMesh& skin, const TriMesh& skull, const std::vector<MuscleShape>& muscles,
                  const SkinMuscleModelOptions& model_options = {},
                  const MuscleContractionOptions& contraction_options = {});

  /// Skin positions for free activations (see resolve_activations()).
  FaceExpression pose(const std::string& name, const MuscleActivations& activations) const;
  /// Skin positions for a preset (expression_preset()).
  FaceExpression preset(const std::string& name) const;

  const SkinMuscleModel& model() const { return m_model; }
  const MuscleContractionSolver& solver() const { return *m_solver; }

 private:
  SkinMuscleModel m_model;
  std::unique_ptr<MuscleContractionSolver> m_solver;
};

/// glTF morph targets of `expressions` on `neutral_skin` (welded; its positions the rest state): per target
/// the expression's name, position deltas (expression - neutral, mm) and normal deltas (area-weighted vertex
/// normals of the expression minus those of the neutral skin). Throws InputError when an expression's
/// vertex count differs from the skin's.
std::vector<MorphTarget> expression_morph_targets(const TriMesh& neutral_skin,
                                                  const std::vector<FaceExpression>& expressions);

/// Morph targets of the presets `expression_names` (expression_preset_names(); "neutral" gives a zero
/// target) on a head: builds its FaceExpressions once, poses each preset and returns
/// expression_morph_targets() of the poses, in the order given, named after the presets. `skin`, `skull`,
/// `muscles` as for FaceExpressions. Throws InputError for an unknown or repeated name (with the closest
/// preset), and as FaceExpressions does.
std::vector<MorphTarget> expression_morph_targets(const TriMesh& skin, const TriMesh& skull,
                                                  const std::vector<MuscleShape>& muscles,
                                                  const std::vector<std::string>& expression_names,
                                                  const SkinMuscleModelOptions& model_options = {},
                                                  const MuscleContractionOptions& contraction_options = {});

/// The same on a fitted head (TemplateFit::result()): its skin and muscles under the target `skull` (the
/// skull the template was fitted to, mm, the head's frame). The targets index fit.skin's welded vertices:
/// write them as the morph targets of the GltfMeshNode whose mesh is fit.skin.
std::vector<MorphTarget> expression_morph_targets(const TemplateFitResult& fit, const TriMesh& skull,
                                                  const std::vector<std::string>& expression_names,
                                                  const SkinMuscleModelOptions& model_options = {},
                                                  const MuscleContractionOptions& contraction_options = {});

/// Where surface points of the neutral skin (landmarks such as ch'_L) go in an expression: each point is
/// located on its closest neutral triangle and moved with that triangle's displaced corners (barycentric).
std::vector<Vec3> track_skin_points(const TriMesh& neutral_skin, const std::vector<Vec3>& displaced_positions,
                                    const std::vector<Vec3>& points);

}  // namespace forensim
