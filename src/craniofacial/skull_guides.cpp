#include "craniofacial/skull_guides.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/error.hpp"
#include "craniofacial/face_guides_job.hpp"
#include "craniofacial/head_frame.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/ray_caster.hpp"

namespace forensim {
namespace {

const std::string source = "skull guides";

// Head directions: the head frame when the landmarks give one (porions, orbitale, midline points), else LPS.
bool head_directions(const LandmarkSet& landmarks, const HeadFrame* given, Vec3& lateral, Vec3& up) {
  lateral = Vec3::UnitX();
  up = Vec3::UnitZ();
  std::optional<HeadFrame> frame;
  if (given) {
    frame = *given;
  } else {
    try {
      frame = head_frame_from_landmarks(landmarks);
    } catch (const InputError&) {
      return false;
    }
  }
  lateral = frame->axes.col(0).normalized();
  up = (frame->axes.col(2) - frame->axes.col(2).dot(lateral) * lateral).normalized();
  return true;
}

const Landmark* first_of(const LandmarkSet& l, std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (const Landmark* found = l.find(n)) return found;
  return nullptr;
}

struct ApertureLine {
  double width = 0.0, left = 0.0, right = 0.0;  // lateral coordinates of the edges (relative to the midline)
};

// One horizontal line of rays at height `h` (up coordinate relative to `centre`): the aperture's edges, or
// nothing when the midline is not an opening.
std::optional<ApertureLine> aperture_line(const RayCaster& caster, const Vec3& centre, const Vec3& lateral,
                                          const Vec3& up, const Vec3& anterior, double h, double front_distance,
                                          double face_front, const SkullGuideOptions& o) {
  // Depth of the first hit behind the start plane, +inf for rays that pass through.
  auto depth = [&](double x) {
    const Vec3 origin = centre + x * lateral + h * up + front_distance * anterior;
    const auto hit = caster.intersect(origin, -anterior, 0.0, 3.0 * front_distance);
    return hit ? hit->t : std::numeric_limits<double>::infinity();
  };
  const double reach = o.lateral_reference_mm;
  // Depths along the line, and the front of the bone beside the aperture on each side: the shallowest hit
  // out to `reach`. Hits deeper than `aperture_depth_cap_mm` behind the face's front (`face_front`, the ray
  // parameter of the midline landmarks' coronal plane) count as that deep: a ray through the aperture may
  // meet the back of the skull, whose depth says nothing about the aperture.
  const int n = static_cast<int>(std::floor(reach / o.sample_step_mm));
  std::vector<double> d(static_cast<std::size_t>(2 * n + 1));
  for (int i = -n; i <= n; ++i) d[static_cast<std::size_t>(i + n)] = depth(i * o.sample_step_mm);
  const double cap = face_front + o.aperture_depth_cap_mm;
  for (double& v : d) v = std::min(v, cap);
  const double mid = d[static_cast<std::size_t>(n)];
  const double side_left = *std::min_element(d.begin() + n + 1, d.end());
  const double side_right = *std::min_element(d.begin(), d.begin() + n);
  // No bone beside the midline near the face's front: not the aperture (above the maxilla, say).
  if (side_left >= cap || side_right >= cap) return std::nullopt;
  if (mid - std::max(side_left, side_right) < o.min_aperture_depth_mm) return std::nullopt;
  ApertureLine line;
  for (int s : {+1, -1}) {
    const double side = s > 0 ? side_left : side_right;
    const double level = side + o.edge_level * (mid - side);
    double edge = std::numeric_limits<double>::quiet_NaN();
    double previous = mid;
    for (int i = 1; i <= n; ++i) {
      const double here = d[static_cast<std::size_t>(n + s * i)];
      if (here <= level) {
        // Linear interpolation of the crossing between the previous sample and this one.
        const double f = previous > here ? (previous - level) / (previous - here) : 1.0;
        edge = s * (i - 1 + f) * o.sample_step_mm;
        break;
      }
      previous = here;
    }
    if (!std::isfinite(edge)) return std::nullopt;
    (s > 0 ? line.left : line.right) = edge;
  }
  line.width = line.left - line.right;
  return line;
}

// The canine eminence on side `side` (+1 left, -1 right): where the upper alveolar arch turns from facing forward
// to facing sideways. Among the vertices within canine_band_mm of height `height`, on that side of the midline
// (lateral coordinate `mid`), at most canine_depth_mm behind the arch's front (the most anterior vertex within
// 10 mm of the midline in the band), whose normal faces d = (side lateral + anterior) / sqrt 2 (cos > 0.5): the one
// furthest along d. Nothing when no vertex qualifies.
std::optional<Vec3> canine_eminence(const TriMesh& skull, const std::vector<Vec3>& normals, double height, double mid,
                                    int side, const Vec3& lateral, const Vec3& up, const Vec3& anterior,
                                    const SkullGuideOptions& o) {
  double front = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : skull.positions) {
    if (std::abs(p.dot(up) - height) <= o.canine_band_mm && std::abs(p.dot(lateral) - mid) <= 10.0) {
      front = std::max(front, p.dot(anterior));
    }
  }
  if (!std::isfinite(front)) return std::nullopt;
  const Vec3 d = (side * lateral + anterior).normalized();
  std::optional<Vec3> best;
  double best_h = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < skull.positions.size(); ++i) {
    const Vec3& p = skull.positions[i];
    if (std::abs(p.dot(up) - height) > o.canine_band_mm || side * (p.dot(lateral) - mid) <= 0.0 ||
        p.dot(anterior) < front - o.canine_depth_mm || normals[i].dot(d) <= 0.5) {
      continue;
    }
    if (p.dot(d) > best_h) {
      best_h = p.dot(d);
      best = p;
    }
  }
  return best;
}

}  // namespace

SkullGuideMeasurement measure_skull_guides(const TriMesh& skull, const LandmarkSet& landmarks, const HeadFrame* frame,
                                           const SkullGuideOptions& o) {
  require_input(!skull.triangles.empty(), source, "skull", "the skull mesh is empty");
  require_input(o.min_aperture_depth_mm > 0 && o.aperture_depth_cap_mm > o.min_aperture_depth_mm && o.edge_level > 0 &&
                    o.edge_level < 1 && o.lateral_reference_mm > 0 && o.sample_step_mm > 0 && o.line_step_mm > 0 &&
                    o.canine_half_width_mm >= 0 && o.canine_band_mm > 0 && o.canine_depth_mm > 0,
                source, "options", "steps, depths and widths must be positive");
  SkullGuideMeasurement m;
  Vec3 lateral, up;
  m.head_frame = head_directions(landmarks, frame, lateral, up);
  const Vec3 anterior = lateral.cross(up);
  m.guides.lateral = lateral;
  m.guides.up = up;

  // Nasal aperture: the lines up to rhinion, else (none opens there) up to nasion. Where the scan misses the thin
  // nasal bones, rhinion is placed on the maxilla below the opening and only the lines up to nasion cross it.
  const Landmark* bottom = first_of(landmarks, {"ans", "ss"});
  const Landmark* rhinion = landmarks.find("rhi");
  const Landmark* nasion = landmarks.find("n");
  if (!bottom || (!rhinion && !nasion)) {
    m.missing.push_back("nasal_aperture: needs ans or ss, and rhi or n");
  } else {
    const RayCaster caster(skull);
    const BoundingBox box = bounding_box(skull.positions);
    const double front_distance = (box.max - box.min).norm();
    std::optional<ApertureLine> best;
    double best_height = 0.0, best_centre = 0.0;
    for (const Landmark* top : {rhinion, nasion}) {
      if (!top || best) continue;
      // The midline through the two landmarks, at their lateral mean.
      const Vec3 centre = 0.5 * (bottom->position_mm + top->position_mm);
      const double h0 = (bottom->position_mm - centre).dot(up) + 2.0, h1 = (top->position_mm - centre).dot(up) - 2.0;
      const double front_a = std::max(bottom->position_mm.dot(anterior), top->position_mm.dot(anterior));
      const double face_front = centre.dot(anterior) + front_distance - front_a;
      // The lowest run of lines that open, from the spine up: above it bone closes the midline (the nasal bones)
      // or lines open again on other hollows (between the orbits), which are no part of the aperture.
      bool opened = false;
      for (double h = h0; h <= h1; h += o.line_step_mm) {
        const auto line = aperture_line(caster, centre, lateral, up, anterior, h, front_distance, face_front, o);
        if (!line && opened) break;
        opened = opened || line.has_value();
        if (line && (!best || line->width > best->width)) {
          best = line;
          best_height = centre.dot(up) + h;
          best_centre = centre.dot(lateral);
        }
      }
    }
    if (!best) {
      m.missing.push_back("nasal_aperture: no opening found between the nasal spine and rhinion or nasion");
    } else {
      m.guides.nasal_aperture_left_mm = best_centre + best->left;
      m.guides.nasal_aperture_right_mm = best_centre + best->right;
      m.aperture_width_mm = best->width;
      m.aperture_height_mm = best_height;
      m.measured.push_back("nasal_aperture");
    }
  }

  // Nasal spine (Krogman's rule).
  const Landmark* ans = landmarks.find("ans");
  const Landmark* ss = landmarks.find("ss");
  if (!ans || !ss) {
    m.missing.push_back("nasal_spine: needs ans and ss");
  } else {
    const double length = (ans->position_mm - ss->position_mm).dot(anterior);
    if (length <= 0.5) {
      m.missing.push_back("nasal_spine: ans does not stand in front of ss");
    } else {
      m.guides.nasal_spine_tip = ans->position_mm;
      m.guides.nasal_spine_base = ans->position_mm - length * anterior;
      m.spine_length_mm = length;
      m.measured.push_back("nasal_spine");
    }
  }

  // Mouth corners: at the canine / first premolar junctions, half a canine's width lateral of the canine
  // eminences found at the supra-canine points' height (sC_L / sC_R themselves where no eminence is found).
  const Landmark* left = landmarks.find("sC_L");
  const Landmark* right = landmarks.find("sC_R");
  if (!left || !right) {
    m.missing.push_back("mouth_corners: needs sC_L and sC_R");
  } else {
    double l = left->position_mm.dot(lateral), r = right->position_mm.dot(lateral);
    if (l <= r) {
      m.missing.push_back("mouth_corners: sC_L is not to the left of sC_R");
    } else {
      const std::vector<Vec3> normals =
          skull.normals.size() == skull.positions.size() ? skull.normals : vertex_normals(skull);
      const double height = 0.5 * (left->position_mm + right->position_mm).dot(up);
      const double mid = 0.5 * (l + r);
      const auto el = canine_eminence(skull, normals, height, mid, +1, lateral, up, anterior, o);
      const auto er = canine_eminence(skull, normals, height, mid, -1, lateral, up, anterior, o);
      if (el && er && el->dot(lateral) > r && er->dot(lateral) < l) {
        l = el->dot(lateral);
        r = er->dot(lateral);
        m.canine_left_mm = *el;
        m.canine_right_mm = *er;
      }
      m.guides.mouth_corner_left_mm = l + o.canine_half_width_mm;
      m.guides.mouth_corner_right_mm = r - o.canine_half_width_mm;
      m.measured.push_back("mouth_corners");
    }
  }
  return m;
}

FaceGuides merge_face_guides(const FaceGuides& measured, const FaceGuides& given) {
  FaceGuides out = any_guide(given) ? given : measured;
  auto keep = [](auto& slot, const auto& value) {
    if (!slot) slot = value;
  };
  // Measured values are in measured's directions: only take them when the directions agree.
  if ((out.lateral - measured.lateral).norm() < 1e-9 && (out.up - measured.up).norm() < 1e-9) {
    keep(out.nasal_aperture_left_mm, measured.nasal_aperture_left_mm);
    keep(out.nasal_aperture_right_mm, measured.nasal_aperture_right_mm);
    keep(out.mouth_corner_left_mm, measured.mouth_corner_left_mm);
    keep(out.mouth_corner_right_mm, measured.mouth_corner_right_mm);
    keep(out.upper_lip_border_mm, measured.upper_lip_border_mm);
    keep(out.lower_lip_border_mm, measured.lower_lip_border_mm);
    keep(out.lip_parting_mm, measured.lip_parting_mm);
  }
  if (!given.nasal_spine_base && !given.nasal_spine_tip) {
    out.nasal_spine_base = measured.nasal_spine_base;
    out.nasal_spine_tip = measured.nasal_spine_tip;
  }
  return out;
}

}  // namespace forensim
