#include "craniofacial/reconstruction.hpp"

#include <Eigen/QR>
#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "craniofacial/rbf_warp.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/ray_caster.hpp"

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

constexpr double kMaxOutwardMoveMm = 12.0;

/// Depth vectors whose skull normal points against the template's there (a landmark on an inner surface: the
/// palatal side of the alveolar arch, where the outward normal points into the mouth and the skin target would
/// lie inside the head) are moved to where the ray along the template's direction leaves the bone, with that
/// surface's patch normal: the paper's vector is the outward surface normal (section 3). The template's
/// directions are mapped by the least-squares affine map of the bone landmarks of `reference` (normals by its
/// inverse transpose); nothing changes with fewer than 4 of them or a singular map. The bone crossed is at most
/// kMaxOutwardMoveMm thick (the alveolar process with an incisor root): a longer way out runs along a tooth or
/// through the skull, and the landmark stays. Returns how many moved.
std::size_t outward_depth_vectors(const TemplateHead& head, const SkullSurface& surface, const DepthVectors& reference,
                                  DepthVectors& vectors, const DepthVectorOptions& options) {
  std::vector<Vec3> from, to;
  for (const DepthVector& v : reference.vectors) {
    const int j = find_template_landmark(head, v.skin_landmark);
    if (j < 0) continue;
    from.push_back(head.landmarks[static_cast<std::size_t>(j)].skull);
    to.push_back(v.bone_mm);
  }
  if (from.size() < 4) return 0;
  Eigen::MatrixXd m(static_cast<Eigen::Index>(from.size()), 4), y(static_cast<Eigen::Index>(from.size()), 3);
  for (std::size_t i = 0; i < from.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    m.row(r) << from[i].x(), from[i].y(), from[i].z(), 1.0;
    y.row(r) = to[i].transpose();
  }
  const Eigen::MatrixXd solution = m.colPivHouseholderQr().solve(y);  // 4 x 3: [A^T; t^T]
  const Mat3 a = solution.topRows(3).transpose();
  if (!std::isfinite(a.sum()) || std::abs(a.determinant()) < 1e-6) return 0;
  const Mat3 normal_map = a.inverse().transpose();
  std::unique_ptr<RayCaster> rays;
  std::size_t moved = 0;
  for (DepthVector& v : vectors.vectors) {
    const int j = find_template_landmark(head, v.skin_landmark);
    if (j < 0) continue;
    const Vec3 expected = (normal_map * head.landmarks[static_cast<std::size_t>(j)].skull_normal).normalized();
    if (!std::isfinite(expected.sum()) || v.direction.dot(expected) >= 0.0) continue;
    if (!rays) rays = std::make_unique<RayCaster>(surface.mesh());
    double t_min = 1e-3;
    for (int k = 0; k < 16; ++k) {
      const auto hit = rays->intersect(v.bone_mm, expected, t_min, 40.0);
      if (!hit) break;
      if (hit->t > kMaxOutwardMoveMm) break;
      if (hit->normal.dot(expected) > 0.0) {
        const Vec3 direction = surface.landmark_direction(hit->point, options.patch_radius_mm);
        if (direction.dot(expected) > 0.0) {
          v.bone_mm = hit->point;
          v.direction = direction;
          v.skin_mm = v.bone_mm + v.depth_mm * v.direction;
          ++moved;
        }
        break;
      }
      t_min = hit->t + 1e-6;
    }
  }
  return moved;
}

}  // namespace

Reconstruction::Reconstruction(const TemplateHead& head, const TriMesh& skull, const LandmarkSet& skull_landmarks,
                               const TissueDepths& depths, const ReconstructionOptions& options)
    : m_head(head), m_depths(depths), m_options(options), m_surface(skull) {
  m_result.skull_landmarks = canonical_set(skull_landmarks);
  m_result.depth_vectors = depth_vectors(m_surface, m_result.skull_landmarks, m_depths, m_options.depth);
  const DepthVectors as_placed = m_result.depth_vectors;
  outward_depth_vectors(head, m_surface, as_placed, m_result.depth_vectors, m_options.depth);
  const LandmarkDepths given = fit_input(head, m_result.depth_vectors, m_result.used_in_warp, m_result.not_on_template);
  FitTemplateOptions fit_options = m_options.fit;
  fit_options.count_violations = false;  // counted here, after the guides
  m_fit = std::make_unique<TemplateFit>(head, m_surface.mesh(), given, fit_options);
  apply_guides();
  if (m_options.fit.count_violations) count_violations(fit_options.correction.rounds > 0);
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
  DepthVectors moved = depth_vectors(m_surface, one, m_depths, m_options.depth);
  outward_depth_vectors(m_head, m_surface, m_result.depth_vectors, moved, m_options.depth);
  m_result.skull_landmarks.set(one[0]);
  if (moved.vectors.empty()) return 0;  // no skin pair or no depth: nothing of the head depends on it
  const DepthVector& v = moved.vectors.front();
  std::size_t i = 0;
  DepthVectors& vectors = m_result.depth_vectors;
  while (i < vectors.vectors.size() && vectors.vectors[i].bone_landmark != canonical) ++i;
  if (i == vectors.vectors.size()) {
    // A landmark the set did not hold: a new landmark set, fitted anew.
    vectors = depth_vectors(m_surface, m_result.skull_landmarks, m_depths, m_options.depth);
    const DepthVectors as_placed = vectors;
    outward_depth_vectors(m_head, m_surface, as_placed, vectors, m_options.depth);
    const LandmarkDepths given = fit_input(m_head, vectors, m_result.used_in_warp, m_result.not_on_template);
    FitTemplateOptions fit_options = m_options.fit;
    fit_options.count_violations = false;
    m_fit = std::make_unique<TemplateFit>(m_head, m_surface.mesh(), given, fit_options, m_fit->violation_counter());
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
  {
    const DepthVectors as_placed = vectors;
    outward_depth_vectors(m_head, m_surface, as_placed, vectors, m_options.depth);
  }
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
  count_violations(false);
}

void Reconstruction::count_violations(bool fit_counted) {
  const TemplateFitResult& fit = m_fit->result();
  // The warp with the given pairs only (Figure 6a), on the template's skin.
  const std::size_t n = fit.given_pair_count;
  const std::vector<Vec3> sources(fit.sources.begin(), fit.sources.begin() + static_cast<long>(n));
  const std::vector<Vec3> targets(fit.targets.begin(), fit.targets.begin() + static_cast<long>(n));
  TriMesh given_skin = m_head.skin;
  given_skin.positions = RbfWarp(sources, targets, "skull landmarks").evaluate_batch(m_head.skin.positions);
  compute_normals(given_skin);
  // The fit's counter remembers the skins it counted last: the fit's own and the guided one are near each other.
  m_result.violations_interpolated = fit_counted ? fit.violations : m_fit->count_violations(fit.skin);
  m_result.violations_final =
      m_options.guides ? m_fit->count_violations(m_result.skin) : m_result.violations_interpolated;
  m_result.violations_given_only = m_fit->count_violations(given_skin);
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
                      {"interpolated_pairs", fit.interpolated.names.size()},
                      {"correction_pairs", fit.corrections.sources.size()},
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
  const TemplateFitResult& fit = m_fit->result();
  if (m_options.fit.correction.rounds > 0) {
    // The interpolated pairs' own result, and what the correction pairs at the remaining violations added.
    out["before_correction"] = violation_record(fit.violations_before_correction);
    out["correction"] = {{"pairs", fit.corrections.sources.size()},
                         {"rounds", fit.correction_rounds},
                         {"depth", "smallest tissue depth among the 3 nearest given landmarks"}};
  }
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
    fit = std::make_unique<TemplateFit>(m_head, m_surface.mesh(), given, fit_options,
                                        m_fit->violation_counter());  // throws when degenerate
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
