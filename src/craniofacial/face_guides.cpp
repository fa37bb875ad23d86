#include "craniofacial/face_guides.hpp"

#include <cmath>

#include "core/error.hpp"
#include "craniofacial/rbf_warp.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {
namespace {

void check_finite(const std::optional<double>& v, const char* name) {
  require_input(!v || std::isfinite(*v), "face guides", name, "must be finite");
}

/// p with its coordinate along unit `axis` set to `value`.
Vec3 with_coordinate(const Vec3& p, const Vec3& axis, double value) {
  return p + (value - p.dot(axis)) * axis;
}

}  // namespace

GuidedHead apply_face_guides(const TemplateHead& head, const TemplateFitResult& fit, const FaceGuides& guides) {
  const char* const source = "face guides";
  require_input(std::abs(guides.lateral.norm() - 1.0) < 1e-6 && std::abs(guides.up.norm() - 1.0) < 1e-6 &&
                    std::abs(guides.lateral.dot(guides.up)) < 1e-6,
                source, "lateral, up", "must be orthogonal unit vectors");
  check_finite(guides.nasal_aperture_left_mm, "nasal_aperture_left_mm");
  check_finite(guides.nasal_aperture_right_mm, "nasal_aperture_right_mm");
  check_finite(guides.mouth_corner_left_mm, "mouth_corner_left_mm");
  check_finite(guides.mouth_corner_right_mm, "mouth_corner_right_mm");
  check_finite(guides.upper_lip_border_mm, "upper_lip_border_mm");
  check_finite(guides.lower_lip_border_mm, "lower_lip_border_mm");
  check_finite(guides.lip_parting_mm, "lip_parting_mm");
  require_input(std::isfinite(guides.alar_offset_mm) && std::isfinite(guides.krogman_factor), source,
                "alar_offset_mm, krogman_factor", "must be finite");
  require_input(fit.skin.positions.size() == head.skin.positions.size(), source, "fit",
                "does not come from this template head");
  const Vec3 anterior = guides.lateral.cross(guides.up);

  // The landmark set of the second warp: every pair's target and every skin-only landmark where the fit put
  // them; the guides then move some of them.
  std::vector<std::string> names = fit.pair_names;
  std::vector<Vec3> sources = fit.targets;
  for (const TemplateSkinLandmark& l : fit.skin_landmarks) {
    names.push_back(l.name);
    sources.push_back(l.position);
  }
  std::vector<Vec3> targets = sources;
  auto find = [&](const std::string& name) -> long {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) return static_cast<long>(i);
    }
    return -1;
  };
  GuidedHead out;
  auto move = [&](const std::string& name, const Vec3& to) {
    const long i = find(name);
    require_input(i >= 0, source, name, "the fit has no landmark of this name for the rule");
    targets[static_cast<std::size_t>(i)] = to;
  };
  auto current = [&](const std::string& name) {
    const long i = find(name);
    require_input(i >= 0, source, name, "the fit has no landmark of this name for the rule");
    return targets[static_cast<std::size_t>(i)];
  };

  if (guides.nasal_aperture_left_mm) {
    move("al'_L",
         with_coordinate(current("al'_L"), guides.lateral, *guides.nasal_aperture_left_mm + guides.alar_offset_mm));
  }
  if (guides.nasal_aperture_right_mm) {
    move("al'_R",
         with_coordinate(current("al'_R"), guides.lateral, *guides.nasal_aperture_right_mm - guides.alar_offset_mm));
  }
  require_input(guides.nasal_spine_base.has_value() == guides.nasal_spine_tip.has_value(), source, "nasal spine",
                "give both its base and its tip");
  if (guides.nasal_spine_base) {
    const Vec3 base = *guides.nasal_spine_base, tip = *guides.nasal_spine_tip;
    require_input(std::isfinite(base.sum()) && std::isfinite(tip.sum()), source, "nasal spine", "must be finite");
    const double length = (tip - base).norm();
    require_input(length > 0.0, source, "nasal spine", "has zero length");
    const Vec3 u = (tip - base) / length;
    require_input(u.dot(anterior) > 0.2, source, "nasal spine", "must point forward (base behind tip)");
    const double front = current("mp'").dot(anterior) + guides.krogman_factor * length;
    move("prn'", tip + (front - tip.dot(anterior)) / u.dot(anterior) * u);
  }
  if (guides.mouth_corner_left_mm)
    move("ch'_L", with_coordinate(current("ch'_L"), guides.lateral, *guides.mouth_corner_left_mm));
  if (guides.mouth_corner_right_mm) {
    move("ch'_R", with_coordinate(current("ch'_R"), guides.lateral, *guides.mouth_corner_right_mm));
  }
  if (guides.upper_lip_border_mm) move("ls'", with_coordinate(current("ls'"), guides.up, *guides.upper_lip_border_mm));
  if (guides.lower_lip_border_mm) move("li'", with_coordinate(current("li'"), guides.up, *guides.lower_lip_border_mm));
  if (guides.lip_parting_mm) {
    for (const char* name : {"ch'_L", "ch'_R", "sto'"}) {
      move(name, with_coordinate(current(name), guides.up, *guides.lip_parting_mm));
    }
  }

  for (std::size_t i = 0; i < names.size(); ++i) {
    if (targets[i] == sources[i]) continue;
    out.adjusted.push_back(names[i]);
    out.adjusted_from.push_back(sources[i]);
    out.adjusted_to.push_back(targets[i]);
  }
  std::vector<Vec3> points = fit.skin.positions;
  for (const MuscleLayout& m : fit.muscle_layouts) points.insert(points.end(), m.grid.begin(), m.grid.end());
  const RbfWarp warp(sources, targets, "guided landmark set");
  const std::vector<Vec3> moved = warp.evaluate_batch(points);
  out.max_landmark_residual_mm = warp.max_landmark_residual();
  out.skin = fit.skin;
  for (std::size_t v = 0; v < out.skin.positions.size(); ++v) out.skin.positions[v] = moved[v];
  compute_normals(out.skin);
  std::size_t offset = out.skin.positions.size();
  out.muscle_layouts = fit.muscle_layouts;
  for (MuscleLayout& m : out.muscle_layouts) {
    for (Vec3& p : m.grid) p = moved[offset++];
  }
  if (!out.muscle_layouts.empty()) out.muscles = shape_muscles(out.muscle_layouts, out.skin);
  out.skin_landmarks = fit.skin_landmarks;
  for (TemplateSkinLandmark& l : out.skin_landmarks) l.position = warp.evaluate(l.position);
  return out;
}

}  // namespace forensim
