#include "craniofacial/face_expression.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/job.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {
namespace {

/// The presets of Figure 8 in activations of the 24 muscles (bilateral names).
const std::map<std::string, MuscleActivations>& presets() {
  static const std::map<std::string, MuscleActivations> table = {
      {"neutral", {}},
      {"smile",
       {{"zygomaticus_major", 0.9},
        {"zygomaticus_minor", 0.3},
        {"risorius", 0.4},
        {"levator_anguli_oris", 0.3},
        {"orbicularis_oculi", 0.2}}},
      {"frown",
       {{"corrugator_supercilii", 0.9},
        {"procerus", 0.7},
        {"depressor_anguli_oris", 0.6},
        {"depressor_labii_inferioris", 0.3},
        {"orbicularis_oris", 0.2}}},
      {"worried",
       {{"frontalis", 0.5}, {"corrugator_supercilii", 0.7}, {"depressor_anguli_oris", 0.5}, {"orbicularis_oris", 0.1}}},
      {"surprise", {{"frontalis", 1.0}, {"levator_labii_superioris", 0.3}, {"depressor_labii_inferioris", 0.5}}},
  };
  return table;
}

std::string closest_name(const std::string& name, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(name, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

bool has_side(const std::string& name) {
  return name.size() > 2 && (name.ends_with("_L") || name.ends_with("_R"));
}

}  // namespace

std::vector<std::string> expression_preset_names() {
  return {"neutral", "smile", "frown", "worried", "surprise"};
}

std::vector<std::string> parse_expression_list(const std::string& text, const std::string& source) {
  std::vector<std::string> names;
  if (text == "none") return names;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    std::string name = text.substr(start, comma - start);
    if (name.empty()) throw InputError(source, text, "empty name in the list (use 'none' for no expressions)");
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(std::move(name));
    start = comma + 1;
  }
  return names;
}

MuscleActivations expression_preset(const std::string& name) {
  const auto it = presets().find(name);
  if (it == presets().end()) {
    throw InputError("expression preset", name,
                     "unknown preset; did you mean \"" + closest_name(name, expression_preset_names()) + "\"?");
  }
  return it->second;
}

std::vector<double> resolve_activations(const std::vector<std::string>& muscle_names,
                                        const MuscleActivations& activations) {
  std::vector<std::string> accepted = muscle_names;
  for (const std::string& m : muscle_names) {
    if (has_side(m)) accepted.push_back(m.substr(0, m.size() - 2));
  }
  std::vector<double> out(muscle_names.size(), 0.0);
  for (const auto& [name, value] : activations) {
    require_input(std::isfinite(value) && value >= 0.0 && value <= 1.0, "muscle activations", name,
                  "activation must be in [0, 1], got " + std::to_string(value));
    bool found = false;
    for (std::size_t k = 0; k < muscle_names.size(); ++k) {
      const std::string& m = muscle_names[k];
      if (m == name || (has_side(m) && m.substr(0, m.size() - 2) == name)) {
        out[k] = value;
        found = true;
      }
    }
    if (!found) {
      throw InputError("muscle activations", name,
                       "unknown muscle; did you mean \"" + closest_name(name, accepted) + "\"?");
    }
  }
  return out;
}

FaceExpressions::FaceExpressions(const TriMesh& skin, const TriMesh& skull, const std::vector<MuscleShape>& muscles,
                                 const SkinMuscleModelOptions& model_options,
                                 const MuscleContractionOptions& contraction_options)
    : m_model(make_skin_muscle_model(skin, skull, muscles, model_options)),
      m_solver(std::make_unique<MuscleContractionSolver>(m_model, contraction_options)) {}

FaceExpression FaceExpressions::pose(const std::string& name, const MuscleActivations& activations) const {
  const ContractionResult r = m_solver->solve(resolve_activations(m_model.muscle_names, activations));
  FaceExpression e;
  e.name = name;
  e.skin_positions.assign(r.node_positions.begin(),
                          r.node_positions.begin() + static_cast<std::ptrdiff_t>(m_model.skin_node_count));
  e.newton_iterations = r.newton_iterations;
  e.seconds = r.seconds;
  return e;
}

FaceExpression FaceExpressions::preset(const std::string& name) const {
  return pose(name, expression_preset(name));
}

std::vector<MorphTarget> expression_morph_targets(const TriMesh& neutral_skin,
                                                  const std::vector<FaceExpression>& expressions) {
  TriMesh neutral = neutral_skin;
  compute_normals(neutral);
  std::vector<MorphTarget> out;
  for (const FaceExpression& e : expressions) {
    require_input(e.skin_positions.size() == neutral.positions.size(), "expression " + e.name, "skin_positions",
                  "has " + std::to_string(e.skin_positions.size()) + " vertices, the skin " +
                      std::to_string(neutral.positions.size()));
    TriMesh posed = neutral;
    posed.positions = e.skin_positions;
    compute_normals(posed);
    MorphTarget t;
    t.name = e.name;
    t.position_deltas.resize(neutral.positions.size());
    t.normal_deltas.resize(neutral.positions.size());
    for (std::size_t i = 0; i < neutral.positions.size(); ++i) {
      t.position_deltas[i] = e.skin_positions[i] - neutral.positions[i];
      t.normal_deltas[i] = posed.normals[i] - neutral.normals[i];
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<MorphTarget> expression_morph_targets(const TriMesh& skin, const TriMesh& skull,
                                                  const std::vector<MuscleShape>& muscles,
                                                  const std::vector<std::string>& expression_names,
                                                  const SkinMuscleModelOptions& model_options,
                                                  const MuscleContractionOptions& contraction_options) {
  for (std::size_t i = 0; i < expression_names.size(); ++i) {
    expression_preset(expression_names[i]);  // unknown names throw before the model is built
    for (std::size_t j = 0; j < i; ++j) {
      require_input(expression_names[j] != expression_names[i], "expression names", expression_names[i], "is repeated");
    }
  }
  const FaceExpressions expressions(skin, skull, muscles, model_options, contraction_options);
  std::vector<FaceExpression> poses;
  poses.reserve(expression_names.size());
  for (const std::string& name : expression_names) poses.push_back(expressions.preset(name));
  return expression_morph_targets(skin, poses);
}

std::vector<MorphTarget> expression_morph_targets(const TemplateFitResult& fit, const TriMesh& skull,
                                                  const std::vector<std::string>& expression_names,
                                                  const SkinMuscleModelOptions& model_options,
                                                  const MuscleContractionOptions& contraction_options) {
  return expression_morph_targets(fit.skin, skull, fit.muscles, expression_names, model_options, contraction_options);
}

std::vector<Vec3> track_skin_points(const TriMesh& neutral_skin, const std::vector<Vec3>& displaced_positions,
                                    const std::vector<Vec3>& points) {
  require_input(displaced_positions.size() == neutral_skin.positions.size(), "tracked skin", "displaced_positions",
                "must have one position per skin vertex");
  const ClosestPointQuery query(neutral_skin);
  const auto hits = query.query_batch(points);
  std::vector<Vec3> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!hits[i]) throw InputError("tracked skin", "point " + std::to_string(i), "no skin triangle found");
    const Tri& t = neutral_skin.triangles[static_cast<std::size_t>(hits[i]->triangle)];
    const Vec3& w = hits[i]->barycentric;
    out[i] = w(0) * displaced_positions[static_cast<std::size_t>(t[0])] +
             w(1) * displaced_positions[static_cast<std::size_t>(t[1])] +
             w(2) * displaced_positions[static_cast<std::size_t>(t[2])];
  }
  return out;
}

}  // namespace forensim
