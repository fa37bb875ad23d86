#include "craniofacial/fit_template.hpp"

#include <cmath>
#include <map>
#include <set>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/timer.hpp"
#include "craniofacial/rbf_warp.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/ray_caster.hpp"

namespace forensim {
namespace {

/// Positions of `mesh` replaced, normals recomputed (triangles, UVs and the rest kept).
TriMesh with_positions(const TriMesh& mesh, const std::vector<Vec3>& positions, std::size_t offset) {
  TriMesh out = mesh;
  for (std::size_t v = 0; v < out.positions.size(); ++v) out.positions[v] = positions[offset + v];
  compute_normals(out);
  return out;
}

}  // namespace

TemplateFit::TemplateFit(const TemplateHead& head, const TriMesh& skull, const LandmarkDepths& landmarks,
                         const FitTemplateOptions& options, std::shared_ptr<SkullSkinViolationCounter> counter)
    : m_head(head), m_skull(skull), m_options(options), m_counter(std::move(counter)) {
  Stopwatch total;
  const char* const source = "skull landmarks";
  require_input(
      landmarks.skull.size() == landmarks.names.size() && landmarks.depth_vectors.size() == landmarks.names.size(),
      source, "", "names, positions and depth vectors differ in number");
  require_input(!skull.triangles.empty(), "target skull", "", "has no triangles");
  skull.validate("target skull");
  if (m_skull.normals.size() != m_skull.positions.size()) compute_normals(m_skull);
  if (!m_counter) m_counter = std::make_shared<SkullSkinViolationCounter>(m_skull);
  require_input(m_counter->skull().positions == skull.positions && m_counter->skull().triangles == skull.triangles,
                "violation counter", "", "counts another skull than the fit's");
  std::set<int> used;
  for (std::size_t i = 0; i < landmarks.names.size(); ++i) {
    const std::string& name = landmarks.names[i];
    const int j = find_template_landmark(head, name);
    require_input(j >= 0, source, name, "is not a landmark of the template head");
    require_input(used.insert(j).second, source, name, "given twice");
    require_input(std::isfinite(landmarks.skull[i].sum()) && std::isfinite(landmarks.depth_vectors[i].sum()), source,
                  name, "non-finite position or depth vector");
    const TemplateLandmarkPair& pair = head.landmarks[static_cast<std::size_t>(j)];
    m_input_names.push_back(name);
    m_given.names.push_back(pair.bone_name);
    m_given.skull.push_back(landmarks.skull[i]);
    m_given.depth_vectors.push_back(landmarks.depth_vectors[i]);
    m_result.pair_names.push_back(pair.skin_name);
    m_result.sources.push_back(pair.skin);
    m_result.targets.push_back(landmarks.skull[i] + landmarks.depth_vectors[i]);
  }
  m_result.given_pair_count = m_result.pair_names.size();
  // The violation counter's trees (the skull's winding numbers and closest points) are built beside the ray
  // caster and the template's interpolated landmarks.
  const bool counting = options.count_violations || options.correction.rounds > 0;
  parallel_invoke(
      [&] {
        if (counting) m_counter->prepare();
      },
      [&] {
        m_skull_rays = std::make_unique<RayCaster>(m_skull);
        if (options.interpolated_landmarks) {
          // The same generators on the template's skull (with the template's own depths) and on the target's.
          LandmarkDepths on_template;
          for (std::size_t i = 0; i < m_given.names.size(); ++i) {
            const TemplateLandmarkPair& pair =
                head.landmarks[static_cast<std::size_t>(find_template_landmark(head, m_input_names[i]))];
            on_template.names.push_back(pair.bone_name);
            on_template.skull.push_back(pair.skull);
            on_template.depth_vectors.push_back(pair.skin - pair.skull);
          }
          const RayCaster template_skull(head.skull), template_skin(head.skin);
          const InterpolatedLandmarks t =
              interpolate_landmarks(head.skull, template_skull, on_template, options.interpolation);
          m_template_interpolated_names = t.names;
          m_template_interpolated_skin = skin_points_along_normals(template_skin, t);
        }
      });

  // All points the warp moves: the skin's vertices, the skin-only landmarks, then the muscle grids.
  std::vector<Vec3> points = head.skin.positions;
  for (const TemplateSkinLandmark& l : head.skin_landmarks) points.push_back(l.position);
  if (options.muscles) {
    for (const MuscleLayout& m : head.muscles) points.insert(points.end(), m.grid.begin(), m.grid.end());
  }

  if (options.count_violations) {
    const RbfWarp given(m_result.sources, m_result.targets, "skull landmarks");
    const std::vector<Vec3> skin = given.evaluate_batch(head.skin.positions);
    m_result.violations_given_only = m_counter->count(with_positions(head.skin, skin, 0));
  }

  m_points = std::move(points);
  factor(target_interpolation(), options.count_violations && options.correction.rounds <= 0);
  if (options.correction.rounds > 0) correct_violations();
  m_result.seconds_total = total.seconds();
}

InterpolatedLandmarks TemplateFit::target_interpolation() const {
  if (!m_options.interpolated_landmarks) return {};
  return interpolate_landmarks(m_skull, *m_skull_rays, m_given, m_options.interpolation);
}

std::vector<std::string> TemplateFit::kept_interpolated_names(const InterpolatedLandmarks& s) const {
  std::set<std::string> on_target(s.names.begin(), s.names.end());
  std::vector<std::string> kept;
  for (const std::string& name : m_template_interpolated_names)
    if (on_target.count(name) > 0) kept.push_back(name);
  return kept;
}

void TemplateFit::factor(const InterpolatedLandmarks& s, bool count_violations, bool shape_muscles_now) {
  // The pair set: the given pairs, then every template interpolated point also found on the target.
  const std::size_t given = m_result.given_pair_count;
  m_result.pair_names.resize(given);
  m_result.sources.resize(given);
  m_result.targets.resize(given);
  for (std::size_t i = 0; i < given; ++i) m_result.targets[i] = m_given.skull[i] + m_given.depth_vectors[i];
  m_interpolated_names.clear();
  m_result.interpolated = InterpolatedLandmarks{};
  std::map<std::string, std::size_t> on_target;
  for (std::size_t i = 0; i < s.names.size(); ++i) on_target.emplace(s.names[i], i);
  for (std::size_t i = 0; i < m_template_interpolated_names.size(); ++i) {
    const auto it = on_target.find(m_template_interpolated_names[i]);
    if (it == on_target.end()) continue;
    const std::size_t k = it->second;
    m_interpolated_names.push_back(m_template_interpolated_names[i]);
    m_result.interpolated.names.push_back(s.names[k]);
    m_result.interpolated.skull.push_back(s.skull[k]);
    m_result.interpolated.normals.push_back(s.normals[k]);
    m_result.interpolated.depth_mm.push_back(s.depth_mm[k]);
    m_result.pair_names.push_back(m_template_interpolated_names[i]);
    m_result.sources.push_back(m_template_interpolated_skin[i]);
    m_result.targets.push_back(s.skull[k] + s.depth_mm[k] * s.normals[k]);
  }
  update_correction_depths();
  const std::vector<Vec3> correction_targets = m_result.corrections.targets();
  for (std::size_t j = 0; j < correction_targets.size(); ++j) {
    m_result.pair_names.push_back("correction_" + std::to_string(j));
    m_result.sources.push_back(m_result.corrections.sources[j]);
    m_result.targets.push_back(correction_targets[j]);
  }
  Stopwatch setup;
  m_warp = std::make_unique<RbfWarp>(m_result.sources, m_result.targets, "landmark pairs");
  // The cardinal functions of the points (#points x #pairs) are made when a landmark first moves (point_warp()): a
  // correction round needs only the warped points, one evaluation of eq. 1 each.
  m_point_warp.reset();
  m_result.seconds_setup = setup.seconds();
  m_warped = m_warp->evaluate_batch(m_points);
  apply_positions(shape_muscles_now);
  m_result.max_landmark_residual_mm = m_warp->max_landmark_residual();
  if (count_violations) recount_violations();
}

const RbfPointWarp& TemplateFit::point_warp() {
  if (!m_point_warp) m_point_warp = std::make_unique<RbfPointWarp>(*m_warp, m_points);
  return *m_point_warp;
}

void TemplateFit::update_correction_depths() {
  ViolationCorrectionPairs& c = m_result.corrections;
  for (std::size_t j = 0; j < c.depth_mm.size(); ++j)
    c.depth_mm[j] = correction_depth(c.neighbours[j], m_given.depth_vectors);
}

std::size_t TemplateFit::correct_violations() {
  const ViolationCorrectionOptions& o = m_options.correction;
  SkullSkinViolations v = m_counter->count(m_result.skin);
  m_result.violations_before_correction = v;
  std::size_t added = 0;
  ViolationCorrectionOptions spaced = o;
  for (int round = 0; round < o.rounds && v.total() > 0; ++round) {
    ViolationCorrectionPairs more;
    for (;;) {
      more =
          violation_correction_pairs(m_skull, m_counter->skull_closest(), m_head.skin, m_result.skin, v, m_given.skull,
                                     m_given.depth_vectors, m_result.sources, m_result.targets, spaced);
      if (!more.sources.empty() || 0.5 * spaced.spacing_mm < o.min_spacing_mm) break;
      spaced.spacing_mm *= 0.5;
    }
    if (more.sources.empty()) break;
    ViolationCorrectionPairs& c = m_result.corrections;
    c.sources.insert(c.sources.end(), more.sources.begin(), more.sources.end());
    c.skull.insert(c.skull.end(), more.skull.begin(), more.skull.end());
    c.normals.insert(c.normals.end(), more.normals.begin(), more.normals.end());
    c.neighbours.insert(c.neighbours.end(), more.neighbours.begin(), more.neighbours.end());
    c.depth_mm.insert(c.depth_mm.end(), more.depth_mm.begin(), more.depth_mm.end());
    added += more.sources.size();
    ++m_result.correction_rounds;
    // factor() rebuilds the interpolated record from its argument: pass a copy. The rounds count the skin only;
    // the muscles are shaped once, under the final skin.
    const InterpolatedLandmarks kept = m_result.interpolated;
    factor(kept, false, false);
    v = m_counter->count(m_result.skin);
  }
  if (added > 0) apply_positions();
  m_result.violations = v;
  return added;
}

TemplateFit::~TemplateFit() = default;

void TemplateFit::apply_positions(bool shape_muscles_now) {
  m_result.skin = with_positions(m_head.skin, m_warped, 0);
  std::size_t offset = m_head.skin.positions.size();
  m_result.skin_landmarks = m_head.skin_landmarks;
  for (TemplateSkinLandmark& l : m_result.skin_landmarks) l.position = m_warped[offset++];
  if (!m_options.muscles || !shape_muscles_now) return;
  m_result.muscle_layouts = m_head.muscles;
  for (MuscleLayout& m : m_result.muscle_layouts) {
    for (Vec3& p : m.grid) p = m_warped[offset++];
  }
  m_result.muscles = shape_muscles(m_result.muscle_layouts, m_result.skin);
}

std::size_t TemplateFit::move_landmark(const std::string& name, const Vec3& skull_position, const Vec3& depth_vector) {
  std::size_t i = 0;
  while (i < m_input_names.size() && m_input_names[i] != name) ++i;
  require_input(i < m_input_names.size(), "moved landmark", name, "is not one of the fit's landmarks");
  require_input(std::isfinite(skull_position.sum()) && std::isfinite(depth_vector.sum()), "moved landmark", name,
                "non-finite position or depth vector");
  m_given.skull[i] = skull_position;
  m_given.depth_vectors[i] = depth_vector;
  return retarget(feeds_interpolation(m_given.names[i]));
}

int TemplateFit::feeds_interpolation(const std::string& bone_name) const {
  if (m_template_interpolated_names.empty()) return 0;
  // What interpolate_landmarks reads: the cranium frame and breadth, and the mandible arcs' ends.
  const LandmarkInterpolationOptions& o = m_options.interpolation;
  int feeds = 0;
  if (o.cranium) {
    for (const char* name : {"g", "v", "op", "zy_L", "zy_R"})
      if (bone_name == name) feeds |= k_cranium;
  }
  if (o.mandible) {
    for (const LandmarkArc& arc : o.mandible_arcs)
      if (bone_name == arc.from || bone_name == arc.to) feeds |= k_mandible;
  }
  return feeds;
}

std::size_t TemplateFit::set_landmarks(const std::vector<Vec3>& skull_positions,
                                       const std::vector<Vec3>& depth_vectors) {
  require_input(skull_positions.size() == m_given.names.size() && depth_vectors.size() == m_given.names.size(),
                "fit landmarks", "", "positions and depth vectors must come one per landmark of the fit");
  for (std::size_t i = 0; i < skull_positions.size(); ++i) {
    require_input(std::isfinite(skull_positions[i].sum()) && std::isfinite(depth_vectors[i].sum()), "fit landmarks",
                  m_input_names[i], "non-finite position or depth vector");
  }
  m_given.skull = skull_positions;
  m_given.depth_vectors = depth_vectors;
  return retarget(k_cranium | k_mandible);
}

std::size_t TemplateFit::retarget(int regenerate) {
  if (regenerate == 0) return retarget_with(m_result.interpolated);
  InterpolatedLandmarks s;
  if (regenerate == (k_cranium | k_mandible)) {
    s = target_interpolation();
  } else {
    // One generator again (the cranium cap's points are named "cranium_..."), the other's points kept.
    LandmarkInterpolationOptions one = m_options.interpolation;
    one.cranium = one.cranium && (regenerate & k_cranium) != 0;
    one.mandible = one.mandible && (regenerate & k_mandible) != 0;
    const InterpolatedLandmarks fresh = interpolate_landmarks(m_skull, *m_skull_rays, m_given, one);
    const InterpolatedLandmarks& old = m_result.interpolated;
    for (std::size_t i = 0; i < old.names.size(); ++i) {
      const bool cranial = old.names[i].rfind("cranium_", 0) == 0;
      if (cranial == ((regenerate & k_cranium) != 0)) continue;
      s.names.push_back(old.names[i]);
      s.skull.push_back(old.skull[i]);
      s.normals.push_back(old.normals[i]);
      s.depth_mm.push_back(old.depth_mm[i]);
    }
    s.names.insert(s.names.end(), fresh.names.begin(), fresh.names.end());
    s.skull.insert(s.skull.end(), fresh.skull.begin(), fresh.skull.end());
    s.normals.insert(s.normals.end(), fresh.normals.begin(), fresh.normals.end());
    s.depth_mm.insert(s.depth_mm.end(), fresh.depth_mm.begin(), fresh.depth_mm.end());
  }
  if (kept_interpolated_names(s) != m_interpolated_names) {
    // An interpolated point appeared or vanished: a new landmark set, factored anew from the whole set.
    if (regenerate != (k_cranium | k_mandible)) s = target_interpolation();
    factor(s, false);
    return m_result.targets.size();
  }
  return retarget_with(s);
}

std::size_t TemplateFit::retarget_with(const InterpolatedLandmarks& s) {
  std::vector<Vec3> targets(m_result.targets.size());
  const std::size_t given = m_result.given_pair_count;
  for (std::size_t j = 0; j < given; ++j) targets[j] = m_given.skull[j] + m_given.depth_vectors[j];
  InterpolatedLandmarks record = m_result.interpolated;
  if (!m_interpolated_names.empty()) {
    std::map<std::string, std::size_t> on_target;
    for (std::size_t k = 0; k < s.names.size(); ++k) on_target.emplace(s.names[k], k);
    for (std::size_t j = 0; j < m_interpolated_names.size(); ++j) {
      const std::size_t k = on_target.at(m_interpolated_names[j]);
      record.skull[j] = s.skull[k];
      record.normals[j] = s.normals[k];
      record.depth_mm[j] = s.depth_mm[k];
      targets[given + j] = s.skull[k] + s.depth_mm[k] * s.normals[k];
    }
  }
  update_correction_depths();
  const std::vector<Vec3> correction_targets = m_result.corrections.targets();
  const std::size_t first_correction = given + m_interpolated_names.size();
  for (std::size_t j = 0; j < correction_targets.size(); ++j) targets[first_correction + j] = correction_targets[j];
  std::vector<std::size_t> changed;
  for (std::size_t j = 0; j < targets.size(); ++j) {
    if (targets[j] != m_result.targets[j]) changed.push_back(j);
  }
  // Few changes: add each one's cardinal function; many (the cranium frame moved): one product.
  if (changed.size() * 4 < targets.size()) {
    const RbfPointWarp& cardinal = point_warp();
    for (const std::size_t j : changed) cardinal.move_target(j, targets[j] - m_result.targets[j], m_warped);
  } else {
    m_warped = point_warp().warp(targets);
  }
  for (const std::size_t j : changed) m_warp->set_target(j, targets[j]);
  m_result.targets = targets;
  m_result.interpolated = std::move(record);
  apply_positions();
  m_result.max_landmark_residual_mm = m_warp->max_landmark_residual();
  return changed.size();
}

void TemplateFit::recount_violations() {
  m_result.violations = m_counter->count(m_result.skin);
}

SkullSkinViolations TemplateFit::count_violations(const TriMesh& skin) {
  return m_counter->count(skin);
}

TemplateFitResult fit_template(const TemplateHead& head, const TriMesh& skull, const LandmarkDepths& landmarks,
                               const FitTemplateOptions& options) {
  return TemplateFit(head, skull, landmarks, options).result();
}

}  // namespace forensim
