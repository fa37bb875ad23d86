#include "craniofacial/reconstruction.hpp"

#include <cmath>

#include "core/error.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "craniofacial/rbf_warp.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {
namespace {

nlohmann::json vec_json(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json violation_record(const SkullSkinViolations& v) {
  return {{"skull_vertices", v.skull_vertex_count},
          {"skin_vertices", v.skin_vertex_count},
          {"skull_outside_skin", v.skull_outside_skin},
          {"skin_inside_skull", v.skin_inside_skull},
          {"max_skull_protrusion_mm", v.max_skull_protrusion_mm},
          {"max_skin_intrusion_mm", v.max_skin_intrusion_mm}};
}

/// The set under canonical vocabulary names (two spellings of one landmark collide in add()).
LandmarkSet canonical_set(const LandmarkSet& set) {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const std::string source =
      set.name().empty() ? std::string("skull landmarks") : "skull landmarks '" + set.name() + "'";
  LandmarkSet out(set.name().empty() ? std::string("skull") : set.name());
  for (const Landmark& l : set.landmarks()) {
    Landmark c = l;
    c.name = vocabulary.canonical_name(l.name, source, l.name);
    out.add(std::move(c));
  }
  return out;
}

/// The fit's input from depth vectors: those whose skin landmark the template has.
LandmarkDepths fit_input(const TemplateHead& head, const DepthVectors& vectors, std::vector<bool>& used,
                         std::vector<std::string>& not_on_template) {
  LandmarkDepths given;
  used.assign(vectors.vectors.size(), false);
  not_on_template.clear();
  for (std::size_t i = 0; i < vectors.vectors.size(); ++i) {
    const DepthVector& v = vectors.vectors[i];
    if (find_template_landmark(head, v.skin_landmark) < 0) {
      not_on_template.push_back(v.bone_landmark);
      continue;
    }
    used[i] = true;
    given.names.push_back(v.skin_landmark);
    given.skull.push_back(v.bone_mm);
    given.depth_vectors.push_back(v.direction * v.depth_mm);
  }
  return given;
}

}  // namespace

Reconstruction::Reconstruction(const TemplateHead& head, const TriMesh& skull, const LandmarkSet& skull_landmarks,
                               const TissueDepths& depths, const ReconstructionOptions& options)
    : m_head(head), m_depths(depths), m_options(options), m_surface(skull) {
  m_result.skull_landmarks = canonical_set(skull_landmarks);
  m_result.depth_vectors = depth_vectors(m_surface, m_result.skull_landmarks, m_depths, m_options.depth);
  const LandmarkDepths given = fit_input(head, m_result.depth_vectors, m_result.used_in_warp, m_result.not_on_template);
  FitTemplateOptions fit_options = m_options.fit;
  fit_options.count_violations = false;  // counted here, after the guides
  m_fit = std::make_unique<TemplateFit>(head, m_surface.mesh(), given, fit_options);
  apply_guides();
  if (m_options.fit.count_violations) recount_violations();
}

Reconstruction::~Reconstruction() = default;

const TemplateFitResult& Reconstruction::fit() const {
  return m_fit->result();
}

const TriMesh& Reconstruction::skull() const {
  return m_surface.mesh();
}

void Reconstruction::apply_guides() {
  const TemplateFitResult& fit = m_fit->result();
  m_result.guides_adjusted.clear();
  m_result.guides_adjusted_from.clear();
  m_result.guides_adjusted_to.clear();
  m_result.guides_max_residual_mm = 0.0;
  if (m_options.guides) {
    GuidedHead guided = apply_face_guides(m_head, fit, *m_options.guides);
    m_result.skin = std::move(guided.skin);
    m_result.muscle_layouts = std::move(guided.muscle_layouts);
    m_result.muscles = std::move(guided.muscles);
    m_result.skin_only_landmarks = std::move(guided.skin_landmarks);
    m_result.guides_adjusted = std::move(guided.adjusted);
    m_result.guides_adjusted_from = std::move(guided.adjusted_from);
    m_result.guides_adjusted_to = std::move(guided.adjusted_to);
    m_result.guides_max_residual_mm = guided.max_landmark_residual_mm;
  } else {
    m_result.skin = fit.skin;
    m_result.muscle_layouts = fit.muscle_layouts;
    m_result.muscles = fit.muscles;
    m_result.skin_only_landmarks = fit.skin_landmarks;
  }
  assemble();
}

void Reconstruction::assemble() {
  m_result.skin_landmarks = skin_landmarks(m_result.depth_vectors);
  for (const TemplateSkinLandmark& l : m_result.skin_only_landmarks) {
    if (!m_result.skin_landmarks.contains(l.name)) {
      m_result.skin_landmarks.add({l.name, l.position, LandmarkSource::detected, 1.0});
    }
  }
  m_result.violations_current = false;
}

std::size_t Reconstruction::move_landmark(const std::string& name, const Vec3& position_mm) {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const std::string canonical = vocabulary.canonical_name(name, "moved landmark", name);
  require_input(std::isfinite(position_mm.sum()), "moved landmark", canonical, "position must be finite");
  LandmarkSet one("moved landmark");
  one.add({canonical, position_mm, LandmarkSource::edited, 1.0});
  const DepthVectors moved = depth_vectors(m_surface, one, m_depths, m_options.depth);
  m_result.skull_landmarks.set(one[0]);
  if (moved.vectors.empty()) return 0;  // no skin pair or no depth: nothing of the head depends on it
  const DepthVector& v = moved.vectors.front();
  std::size_t i = 0;
  DepthVectors& vectors = m_result.depth_vectors;
  while (i < vectors.vectors.size() && vectors.vectors[i].bone_landmark != canonical) ++i;
  if (i == vectors.vectors.size()) {
    // A landmark the set did not hold: a new landmark set, fitted anew.
    vectors = depth_vectors(m_surface, m_result.skull_landmarks, m_depths, m_options.depth);
    const LandmarkDepths given = fit_input(m_head, vectors, m_result.used_in_warp, m_result.not_on_template);
    FitTemplateOptions fit_options = m_options.fit;
    fit_options.count_violations = false;
    m_fit = std::make_unique<TemplateFit>(m_head, m_surface.mesh(), given, fit_options);
    apply_guides();
    return m_fit->result().targets.size();
  }
  vectors.vectors[i] = v;
  std::size_t changed = 0;
  if (m_result.used_in_warp[i]) changed = m_fit->move_landmark(v.skin_landmark, v.bone_mm, v.direction * v.depth_mm);
  apply_guides();
  return changed;
}

std::size_t Reconstruction::set_depths(const TissueDepths& depths) {
  DepthVectors vectors = depth_vectors(m_surface, m_result.skull_landmarks, depths, m_options.depth);
  const DepthVectors& old = m_result.depth_vectors;
  bool same_landmarks = vectors.vectors.size() == old.vectors.size();
  for (std::size_t i = 0; same_landmarks && i < old.vectors.size(); ++i) {
    same_landmarks = vectors.vectors[i].bone_landmark == old.vectors[i].bone_landmark;
  }
  if (!same_landmarks) {
    for (const DepthVector& v : old.vectors) {
      require_input(depths.find_site(LandmarkVocabulary::built_in()
                                         .site(LandmarkVocabulary::built_in().resolve(v.bone_landmark, "tissue depths",
                                                                                      v.bone_landmark))
                                         .abbreviation) != nullptr,
                    "tissue depths '" + depths.table + "'", v.bone_landmark, "has no depth for this landmark");
    }
  }
  m_depths = depths;
  m_result.depth_vectors = std::move(vectors);
  std::vector<Vec3> skull, depth;
  for (std::size_t i = 0; i < m_result.depth_vectors.vectors.size(); ++i) {
    if (!m_result.used_in_warp[i]) continue;
    const DepthVector& v = m_result.depth_vectors.vectors[i];
    skull.push_back(v.bone_mm);
    depth.push_back(v.direction * v.depth_mm);
  }
  const std::size_t changed = m_fit->set_landmarks(skull, depth);
  apply_guides();
  return changed;
}

void Reconstruction::set_guides(const std::optional<FaceGuides>& guides) {
  m_options.guides = guides;
  apply_guides();
}

void Reconstruction::recount_violations() {
  const TemplateFitResult& fit = m_fit->result();
  const TriMesh& skull = m_surface.mesh();
  // The warp with the given pairs only (Figure 6a), on the template's skin.
  const std::size_t n = fit.given_pair_count;
  const std::vector<Vec3> sources(fit.sources.begin(), fit.sources.begin() + static_cast<long>(n));
  const std::vector<Vec3> targets(fit.targets.begin(), fit.targets.begin() + static_cast<long>(n));
  TriMesh given_skin = m_head.skin;
  given_skin.positions = RbfWarp(sources, targets, "skull landmarks").evaluate_batch(m_head.skin.positions);
  compute_normals(given_skin);
  m_result.violations_given_only = count_skull_skin_violations(skull, given_skin);
  m_result.violations_interpolated = count_skull_skin_violations(skull, fit.skin);
  m_result.violations_final =
      m_options.guides ? count_skull_skin_violations(skull, m_result.skin) : m_result.violations_interpolated;
  m_result.violations_current = true;
}

nlohmann::json Reconstruction::provenance() const {
  const TemplateFitResult& fit = m_fit->result();
  const DepthVectors& vectors = m_result.depth_vectors;
  nlohmann::json items = nlohmann::json::array();
  for (std::size_t i = 0; i < vectors.vectors.size(); ++i) {
    const DepthVector& v = vectors.vectors[i];
    items.push_back({{"name", v.bone_landmark},
                     {"skin_landmark", v.skin_landmark},
                     {"source", to_string(v.source)},
                     {"confidence", v.confidence},
                     {"skull_mm", vec_json(v.bone_mm)},
                     {"direction", vec_json(v.direction)},
                     {"depth_mm", v.depth_mm},
                     {"depth_source", v.depth_source},
                     {"skin_mm", vec_json(v.skin_mm)},
                     {"surface_offset_mm", v.surface_offset_mm},
                     {"used_in_warp", static_cast<bool>(m_result.used_in_warp[i])}});
  }
  nlohmann::json out;
  out["landmarks"] = {{"items", items},
                      {"missing_depth", vectors.missing},
                      {"unpaired", vectors.unpaired},
                      {"not_on_template", m_result.not_on_template},
                      {"given_pairs", fit.given_pair_count},
                      {"interpolated_pairs", fit.targets.size() - fit.given_pair_count},
                      {"max_landmark_residual_mm", fit.max_landmark_residual_mm}};
  out["depths"] = {{"table", m_depths.table},
                   {"group", m_depths.group.describe()},
                   {"variant", m_depths.variant},
                   {"notes", m_depths.notes}};
  nlohmann::json adjusted = nlohmann::json::array();
  for (std::size_t i = 0; i < m_result.guides_adjusted.size(); ++i) {
    adjusted.push_back({{"name", m_result.guides_adjusted[i]},
                        {"from_mm", vec_json(m_result.guides_adjusted_from[i])},
                        {"to_mm", vec_json(m_result.guides_adjusted_to[i])}});
  }
  out["guides_adjusted"] = adjusted;
  return out;
}

nlohmann::json Reconstruction::violations_json() const {
  nlohmann::json out = {{"given_pairs_only", violation_record(m_result.violations_given_only)},
                        {"with_interpolated_landmarks", violation_record(m_result.violations_interpolated)}};
  if (m_options.guides) out["after_guides"] = violation_record(m_result.violations_final);
  out["current"] = m_result.violations_current;
  return out;
}

std::size_t Reconstruction::remove_landmark(const std::string& name) {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const std::string canonical = vocabulary.canonical_name(name, "removed landmark", name);
  require_input(m_result.skull_landmarks.contains(canonical), "removed landmark", canonical,
                "is not one of the skull landmarks");
  // The new state is built aside and taken over only once the new fit succeeded.
  LandmarkSet landmarks = m_result.skull_landmarks;
  landmarks.remove(canonical);
  DepthVectors vectors = depth_vectors(m_surface, landmarks, m_depths, m_options.depth);
  std::vector<bool> used;
  std::vector<std::string> not_on_template;
  const LandmarkDepths given = fit_input(m_head, vectors, used, not_on_template);
  const std::vector<std::string>& before = m_fit->result().pair_names;
  const std::size_t before_given = m_fit->result().given_pair_count;
  bool same_pairs = given.names.size() == before_given;
  for (std::size_t i = 0; same_pairs && i < given.names.size(); ++i) {
    const int j = find_template_landmark(m_head, given.names[i]);
    same_pairs = j >= 0 && m_head.landmarks[static_cast<std::size_t>(j)].skin_name == before[i];
  }
  std::unique_ptr<TemplateFit> fit;
  if (!same_pairs) {
    require_input(given.names.size() >= 4, "removed landmark", canonical,
                  "would leave " + std::to_string(given.names.size()) +
                      " landmark pairs for the warp; it needs at least 4 (eq. 1)");
    FitTemplateOptions fit_options = m_options.fit;
    fit_options.count_violations = false;
    fit = std::make_unique<TemplateFit>(m_head, m_surface.mesh(), given, fit_options);  // throws when degenerate
  }
  m_result.skull_landmarks = std::move(landmarks);
  m_result.depth_vectors = std::move(vectors);
  m_result.used_in_warp = std::move(used);
  m_result.not_on_template = std::move(not_on_template);
  if (fit) {
    m_fit = std::move(fit);
    apply_guides();
  } else {
    assemble();  // the warp is unchanged; the skin landmarks follow the depth vectors
  }
  return m_fit->result().targets.size();
}

ReconstructionResult reconstruct_face(const TemplateHead& head, const TriMesh& skull,
                                      const LandmarkSet& skull_landmarks, const TissueDepths& depths,
                                      const ReconstructionOptions& options) {
  return Reconstruction(head, skull, skull_landmarks, depths, options).result();
}

}  // namespace forensim
