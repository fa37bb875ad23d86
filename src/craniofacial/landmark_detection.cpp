#include "craniofacial/landmark_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {

namespace {

LandmarkDefinition extremal(const char* site, Vec3 direction, double radius, bool midline) {
  return {site, LandmarkRule::extremal, midline, direction.normalized(), radius};
}
LandmarkDefinition on_midline(const char* site, double radius) {
  return {site, LandmarkRule::midline, true, Vec3::Zero(), radius};
}
LandmarkDefinition transfer(const char* site) {
  return {site, LandmarkRule::transfer, false, Vec3::Zero(), 0.0};
}

// Head coordinates are LPS: +x left, +y posterior, +z superior; anterior is -y.
std::vector<LandmarkDefinition> built_in_definitions() {
  return {
      extremal("v", Vec3(0, 0, 1), 20.0, true),             // highest point of the vault
      extremal("op", Vec3(0, 1, 0), 20.0, true),            // most posterior point of the cranium
      extremal("g", Vec3(0, -1, 0), 10.0, true),            // most anterior point between the brow ridges
      extremal("n", Vec3(0, 1, 0), 6.0, true),              // deepest point of the frontonasal profile
      on_midline("mn", 6.0),                                // midway along the nasal bones
      on_midline("rhi", 6.0),                               // lower end of the internasal suture
      extremal("ss", Vec3(0, 1, 0), 6.0, true),             // deepest point below the nasal spine (point A)
      on_midline("mp", 6.0),                                // midway subspinale-prosthion
      extremal("pr", Vec3(0, -1, 0), 5.0, true),            // most anterior maxillary alveolar point
      extremal("id", Vec3(0, -1, 0), 5.0, true),            // most anterior mandibular alveolar point
      extremal("sm", Vec3(0, 1, 0), 6.0, true),             // deepest point of the mandibular concavity (point B)
      extremal("pg", Vec3(0, -1, 0), 8.0, true),            // most anterior chin point
      extremal("gn", Vec3(0, -1, -1), 8.0, true),           // midway pogonion-menton on the symphysis outline
      extremal("me", Vec3(0, 0, -1), 8.0, true),            // most inferior symphysis point
      on_midline("sg", 8.0),                                // above glabella
      extremal("ans", Vec3(0, -1, 0), 5.0, true),           // tip of the anterior nasal spine
      extremal("zy", Vec3(1, 0, 0), 10.0, false),           // most lateral arch point
      extremal("go", Vec3(0.4, 0.65, -0.65), 10.0, false),  // the mandibular angle, lateral-posterior-inferior
      transfer("mso"),
      transfer("mio"),
      transfer("ac"),
      transfer("sC"),
      transfer("iC"),
      transfer("ecm2"),
      transfer("ecm2i"),
      transfer("mr"),
      transfer("mmb"),
      transfer("fe"),
      transfer("im"),
      transfer("lo"),
      transfer("sgl"),
      transfer("ol"),
      transfer("po"),
      transfer("or"),
  };
}

/// Candidate points of one refinement: mesh vertices, or for midline sites the points where mesh edges cross
/// the midsagittal plane (the skull's midsagittal profile), each with a normal.
struct Candidates {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;
};

Candidates midline_profile(const TriMesh& mesh, const std::vector<Vec3>& face_normal, const Plane& plane,
                           const Vec3& centre, double reach) {
  Candidates c;
  const double reach2 = reach * reach;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    for (int e = 0; e < 3; ++e) {
      const Index a = t[static_cast<std::size_t>(e)];
      const Index b = t[static_cast<std::size_t>((e + 1) % 3)];
      if (a > b) continue;  // each edge once: in the neighbouring triangle it runs b -> a
      const Vec3& pa = mesh.positions[static_cast<std::size_t>(a)];
      const Vec3& pb = mesh.positions[static_cast<std::size_t>(b)];
      const double da = plane.signed_distance(pa);
      const double db = plane.signed_distance(pb);
      if ((da > 0.0) == (db > 0.0) || da == db) continue;
      const Vec3 x = pa + (da / (da - db)) * (pb - pa);
      if ((x - centre).squaredNorm() > reach2) continue;
      c.points.push_back(x);
      c.normals.push_back(face_normal[f]);
    }
  }
  return c;
}

Candidates vertices_near(const TriMesh& mesh, const std::vector<Vec3>& normals, const Vec3& centre, double reach) {
  Candidates c;
  const double reach2 = reach * reach;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if ((mesh.positions[i] - centre).squaredNorm() > reach2) continue;
    c.points.push_back(mesh.positions[i]);
    c.normals.push_back(normals[i]);
  }
  return c;
}

struct SurfaceNormals {
  std::vector<Vec3> vertex;
  std::vector<Vec3> face;
};

RefinedLandmark refine(const TriMesh& mesh, const SurfaceNormals& normals, const HeadFrame& frame,
                       const LandmarkDefinition& def, Side side, const Vec3& start) {
  const std::size_t n = mesh.positions.size();
  const Plane& plane = frame.midsagittal;
  const double radius = def.search_radius_mm;
  // The sheet the start lies on: the normal of its closest vertex.
  std::size_t nearest = 0;
  double nearest_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const double d2 = (mesh.positions[i] - start).squaredNorm();
    if (d2 < nearest_d2) {
      nearest_d2 = d2;
      nearest = i;
    }
  }
  RefinedLandmark out;
  out.position_mm = mesh.positions[nearest];
  if (def.rule == LandmarkRule::transfer) return out;
  const Vec3 sheet = normals.vertex[nearest];
  const auto admissible = [&](const Vec3& normal) { return sheet.squaredNorm() == 0.0 || normal.dot(sheet) > 0.3; };
  // Candidates within twice the radius: the search ball and the sharpness ring around its extremum.
  const Candidates c = def.midline ? midline_profile(mesh, normals.face, plane, start, 2.0 * radius)
                                   : vertices_near(mesh, normals.vertex, start, 2.0 * radius);
  if (def.rule == LandmarkRule::midline) {
    const Vec3 target = plane.project(start);
    double best = radius * radius;
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const double d2 = (c.points[i] - target).squaredNorm();
      if (d2 <= best && admissible(c.normals[i])) {
        best = d2;
        out.position_mm = c.points[i];
      }
    }
    return out;
  }
  Vec3 dir_head = def.direction_head;
  if (side == Side::right) dir_head.x() = -dir_head.x();
  const Vec3 dir = frame.axes * dir_head;
  std::size_t best = c.points.size();
  double best_h = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    if ((c.points[i] - start).squaredNorm() > radius * radius || !admissible(c.normals[i])) continue;
    const double h = dir.dot(c.points[i]);
    if (h > best_h) {
      best_h = h;
      best = i;
    }
  }
  if (best == c.points.size()) {
    // Nothing admissible: the transferred point, on the profile for midline sites.
    double nearest_profile = std::numeric_limits<double>::infinity();
    for (const Vec3& p : c.points) {
      if ((p - start).squaredNorm() < nearest_profile) {
        nearest_profile = (p - start).squaredNorm();
        out.position_mm = p;
      }
    }
    return out;
  }
  out.position_mm = c.points[best];
  out.at_search_limit = (out.position_mm - start).norm() > 0.85 * radius;
  // Sharpness: the smallest drop of the height over the ring 0.5-1 radius around the extremum.
  double ring_max = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    const double d = (c.points[i] - out.position_mm).norm();
    if (d < 0.5 * radius || d > radius || !admissible(c.normals[i])) continue;
    ring_max = std::max(ring_max, dir.dot(c.points[i]));
  }
  if (std::isfinite(ring_max)) {
    const double drop = std::max(0.0, best_h - ring_max);
    out.sharpness = drop / (drop + 0.02 * radius);
  }
  if (out.at_search_limit) out.sharpness *= 0.5;
  return out;
}

SurfaceNormals normals_of(const TriMesh& mesh) {
  return {mesh.normals.size() == mesh.positions.size() ? mesh.normals : vertex_normals(mesh), face_normals(mesh)};
}

Side side_of(const std::string& name) {
  const auto ref = LandmarkVocabulary::built_in().find(name);
  return ref ? ref->side : Side::none;
}

double half_at(double value, double scale) {
  return 1.0 / (1.0 + (value / scale) * (value / scale));
}

}  // namespace

static LandmarkDetection detect_with_frame(const TriMesh& reference, const LandmarkSet& reference_landmarks,
                                           const HeadFrame* reference_frame, const TriMesh& target,
                                           const LandmarkDetectionOptions& options);

std::string to_string(LandmarkRule rule) {
  switch (rule) {
    case LandmarkRule::transfer:
      return "transfer";
    case LandmarkRule::midline:
      return "midline";
    case LandmarkRule::extremal:
      return "extremal";
  }
  return "transfer";
}

const std::vector<LandmarkDefinition>& landmark_definitions() {
  static const std::vector<LandmarkDefinition> definitions = built_in_definitions();
  return definitions;
}

std::optional<LandmarkDefinition> landmark_definition(const std::string& landmark_name) {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const auto ref = vocabulary.find(landmark_name);
  if (!ref) return std::nullopt;
  const std::string& site = vocabulary.sites()[ref->site].abbreviation;
  for (const LandmarkDefinition& d : landmark_definitions()) {
    if (d.site == site) return d;
  }
  return std::nullopt;
}

RefinedLandmark refine_landmark(const TriMesh& mesh, const HeadFrame& frame, const LandmarkDefinition& definition,
                                Side side, const Vec3& start) {
  require_input(!mesh.positions.empty(), "landmark refinement mesh", "", "the mesh has no vertices");
  require_input(start.allFinite(), "landmark refinement", definition.site, "the start point is not finite");
  require_input(definition.rule == LandmarkRule::transfer || definition.search_radius_mm > 0.0, "landmark refinement",
                definition.site, "the search radius must be positive");
  require_input(definition.rule != LandmarkRule::extremal || definition.direction_head.norm() > 0.0,
                "landmark refinement", definition.site, "an extremal definition needs a direction");
  return refine(mesh, normals_of(mesh), frame, definition, side, start);
}

LandmarkSet refine_landmarks(const TriMesh& mesh, const HeadFrame& frame, const LandmarkSet& rough) {
  require_input(!mesh.positions.empty(), "landmark refinement mesh", "", "the mesh has no vertices");
  const SurfaceNormals normals = normals_of(mesh);
  const auto& ls = rough.landmarks();
  std::vector<RefinedLandmark> refined(ls.size());
  parallel_for(
      0, ls.size(),
      [&](std::size_t i) {
        const LandmarkDefinition def = landmark_definition(ls[i].name).value_or(transfer(""));
        refined[i] = refine(mesh, normals, frame, def, side_of(ls[i].name), ls[i].position_mm);
      },
      1);
  LandmarkSet out(rough.name());
  for (std::size_t i = 0; i < ls.size(); ++i) {
    out.add({ls[i].name, refined[i].position_mm, LandmarkSource::detected, std::clamp(refined[i].sharpness, 0.0, 1.0)});
  }
  return out;
}

LandmarkDetection detect_landmarks(const TriMesh& reference, const LandmarkSet& reference_landmarks,
                                   const TriMesh& target, const LandmarkDetectionOptions& options) {
  require_input(!reference_landmarks.empty(), "reference landmarks", "", "the set is empty");
  for (const char* name : {"po_L", "po_R"}) {
    require_input(reference_landmarks.contains(name), "reference landmarks", name,
                  "missing (the target's Frankfort plane needs po_L, po_R and or_L or or_R)");
  }
  require_input(reference_landmarks.contains("or_L") || reference_landmarks.contains("or_R"), "reference landmarks",
                "or_L", "missing (the target's Frankfort plane needs po_L, po_R and or_L or or_R)");
  return detect_with_frame(reference, reference_landmarks, nullptr, target, options);
}

LandmarkDetection detect_landmarks(const TriMesh& reference, const LandmarkSet& reference_landmarks,
                                   const HeadFrame& reference_frame, const TriMesh& target,
                                   const LandmarkDetectionOptions& options) {
  return detect_with_frame(reference, reference_landmarks, &reference_frame, target, options);
}

static LandmarkDetection detect_with_frame(const TriMesh& reference, const LandmarkSet& reference_landmarks,
                                           const HeadFrame* reference_frame, const TriMesh& target,
                                           const LandmarkDetectionOptions& options) {
  require_input(!reference_landmarks.empty(), "reference landmarks", "", "the set is empty");
  require_input(options.residual_scale_mm > 0.0, "landmark detection", "residual_scale_mm", "must be positive");
  require_input(options.symmetry_scale_mm > 0.0, "landmark detection", "symmetry_scale_mm", "must be positive");
  require_input(options.residual_radius_mm > 0.0, "landmark detection", "residual_radius_mm", "must be positive");

  LandmarkDetection result;
  SkullRegistrationOptions registration_options = options.registration;
  if (reference_frame && !registration_options.similarity.reference_midsagittal) {
    registration_options.similarity.reference_midsagittal = reference_frame->midsagittal;
  }
  result.registration = register_skull(reference, target, registration_options);
  const SkullRegistration& reg = result.registration;
  const auto& ls = reference_landmarks.landmarks();
  LandmarkSet transferred("transferred");
  for (const Landmark& l : ls) transferred.add({l.name, reg.map(l.position_mm), LandmarkSource::detected, 1.0});
  if (reference_frame) {
    const Mat3 r = reg.similarity.rotation;
    const Plane initial{reg.map(reference_frame->midsagittal.point), r * reference_frame->midsagittal.normal};
    const Plane midsagittal = fit_symmetry_plane(target, initial, options.symmetry).plane;
    HeadFrame& f = result.frame;
    const Vec3 z = (r * reference_frame->axes.col(2)).normalized();
    Vec3 x = midsagittal.normal - midsagittal.normal.dot(z) * z;
    require_input(x.norm() > 1e-6, "target skull", "", "the midsagittal plane is parallel to the Frankfort plane");
    x.normalize();
    if (x.dot(r * reference_frame->axes.col(0)) < 0.0) x = -x;
    f.axes.col(0) = x;
    f.axes.col(1) = z.cross(x);
    f.axes.col(2) = z;
    f.origin = midsagittal.project(reg.map(reference_frame->origin));
    f.frankfort = Plane{f.origin, z};
    f.midsagittal = midsagittal;
    f.perpendicularity_deg =
        std::abs(90.0 - std::acos(std::clamp(midsagittal.normal.dot(z), -1.0, 1.0)) * 180.0 / M_PI);
  } else {
    result.frame = head_frame_from_skull(target, transferred, options.symmetry);
  }
  const HeadFrame& frame = result.frame;

  const SurfaceNormals normals = normals_of(target);
  std::vector<RefinedLandmark> refined(ls.size());
  std::vector<LandmarkDefinition> defs(ls.size());
  for (std::size_t i = 0; i < ls.size(); ++i) defs[i] = landmark_definition(ls[i].name).value_or(transfer(""));
  // A landmark the scan did not see stays where the registration put it (on the reference's missing part).
  const ScanFieldOfView& view = options.registration.similarity.target_view;
  std::vector<char> in_view(ls.size());
  for (std::size_t i = 0; i < ls.size(); ++i) in_view[i] = static_cast<char>(view.contains(transferred[i].position_mm));
  parallel_for(
      0, ls.size(),
      [&](std::size_t i) {
        if (!in_view[i]) {
          refined[i].position_mm = transferred[i].position_mm;
          return;
        }
        refined[i] = refine(target, normals, frame, defs[i], side_of(ls[i].name), transferred[i].position_mm);
      },
      1);

  // Nasal bones the scan did not resolve: nasion to rhinion crosses the aperture, and mn and rhi lie on no bone.
  std::vector<char> left_out(ls.size(), 0);
  const auto n_index = reference_landmarks.index_of("n");
  const auto rhi_index = reference_landmarks.index_of("rhi");
  if (options.nasal_bone_gap_mm > 0.0 && n_index && rhi_index && in_view[*n_index] && in_view[*rhi_index]) {
    const double gap = nasal_bone_gap_mm(target, refined[*n_index].position_mm, refined[*rhi_index].position_mm);
    if (gap > options.nasal_bone_gap_mm) {
      for (const char* name : {"mn", "rhi"}) {
        const auto j = reference_landmarks.index_of(name);
        if (!j) continue;
        left_out[*j] = 1;
        result.left_out.emplace_back(name, fmt::format("the scan shows no nasal bones: the midline from nasion to the "
                                                       "rhinion found runs {:.1f} mm clear of the skull (more than "
                                                       "{:.1f} mm), across the nasal aperture",
                                                       gap, options.nasal_bone_gap_mm));
      }
    }
  }

  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  result.landmarks = LandmarkSet("detected");
  for (std::size_t i = 0; i < ls.size(); ++i) {
    if (left_out[i]) continue;
    DetectedLandmark d;
    d.name = ls[i].name;
    d.rule = defs[i].rule;
    d.transferred_mm = transferred[i].position_mm;
    d.refined_mm = refined[i].position_mm;
    d.residual_mm = reg.local_residual_mm(d.refined_mm, options.residual_radius_mm);
    d.sharpness = defs[i].rule == LandmarkRule::extremal ? refined[i].sharpness : options.transfer_definition_score;
    d.in_view = in_view[i] != 0;
    if (!d.in_view) d.sharpness = 0.0;
    const auto ref = vocabulary.find(d.name);
    bool symmetric_known = false;
    if (ref && ref->side != Side::none) {
      LandmarkRef other = *ref;
      other.side = ref->side == Side::left ? Side::right : Side::left;
      if (const auto j = reference_landmarks.index_of(vocabulary.name(other))) {
        d.symmetry_error_mm = (frame.midsagittal.reflect(d.refined_mm) - refined[*j].position_mm).norm();
        symmetric_known = true;
      }
    } else if (ref && vocabulary.sites()[ref->site].laterality == Laterality::midline) {
      d.symmetry_error_mm = std::abs(frame.midsagittal.signed_distance(d.transferred_mm));
      symmetric_known = true;
    }
    const double c_res = half_at(d.residual_mm, options.residual_scale_mm);
    const double c_sym = symmetric_known ? half_at(d.symmetry_error_mm, options.symmetry_scale_mm) : 1.0;
    d.confidence = std::clamp(std::cbrt(c_res * std::clamp(d.sharpness, 0.0, 1.0) * c_sym), 0.0, 1.0);
    result.landmarks.add({d.name, d.refined_mm, LandmarkSource::detected, d.confidence});
    result.details.push_back(d);
  }
  return result;
}

double nasal_bone_gap_mm(const TriMesh& mesh, const Vec3& nasion, const Vec3& rhinion) {
  require_input(!mesh.positions.empty(), "nasal bone check mesh", "", "the mesh has no vertices");
  double gap = 0.0;
  for (int k = 1; k <= 9; ++k) {
    const Vec3 p = nasion + (0.1 * k) * (rhinion - nasion);
    double nearest2 = std::numeric_limits<double>::infinity();
    for (const Vec3& v : mesh.positions) nearest2 = std::min(nearest2, (v - p).squaredNorm());
    gap = std::max(gap, std::sqrt(nearest2));
  }
  return gap;
}

LandmarkSet locate_landmarks(const TriMesh& skull, const HeadFrame& frame) {
  require_input(!skull.triangles.empty(), "skull", "", "the mesh has no triangles");
  std::vector<Vec3> head(skull.positions.size());
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::size_t i = 0; i < head.size(); ++i) {
    head[i] = frame.to_head(skull.positions[i]);
    lo = lo.cwiseMin(head[i]);
    hi = hi.cwiseMax(head[i]);
  }
  const double height = hi.z() - lo.z();
  const double depth = hi.y() - lo.y();
  const auto z_share = [&](double share) { return lo.z() + share * height; };
  const auto y_share = [&](double share) { return lo.y() + share * depth; };
  // The midsagittal profile in head coordinates.
  const SurfaceNormals normals = normals_of(skull);
  const double reach = 2.0 * (hi - lo).norm();
  const Candidates profile = midline_profile(skull, normals.face, frame.midsagittal, frame.origin, reach);
  LandmarkSet rough("located");
  const auto best_of = [&](const std::vector<Vec3>& points_world, const Vec3& dir_head, auto&& inside) {
    std::optional<Vec3> best;
    double best_h = -std::numeric_limits<double>::infinity();
    for (const Vec3& w : points_world) {
      const Vec3 h = frame.to_head(w);
      if (!inside(h)) continue;
      const double value = dir_head.dot(h);
      if (value > best_h) {
        best_h = value;
        best = w;
      }
    }
    return best;
  };
  const auto add = [&](const std::string& name, const std::optional<Vec3>& p) {
    if (p) rough.add({name, *p, LandmarkSource::detected, 1.0});
  };
  const auto anywhere = [](const Vec3&) { return true; };
  add("v", best_of(profile.points, Vec3(0, 0, 1), anywhere));
  add("op", best_of(profile.points, Vec3(0, 1, 0), anywhere));
  add("g", best_of(profile.points, Vec3(0, -1, 0), [&](const Vec3& h) { return h.z() > z_share(0.55); }));
  const auto chin = [&](const Vec3& h) { return h.z() < z_share(0.2) && h.y() < y_share(0.5); };
  add("pg", best_of(profile.points, Vec3(0, -1, 0), chin));
  add("gn", best_of(profile.points, Vec3(0, -1, -1).normalized(), chin));
  add("me", best_of(profile.points, Vec3(0, 0, -1), chin));
  const auto arch = [&](const Vec3& h) {
    return h.z() > z_share(0.35) && h.z() < z_share(0.6) && h.y() < y_share(0.5);
  };
  add("zy_L", best_of(skull.positions, Vec3(1, 0, 0), arch));
  add("zy_R", best_of(skull.positions, Vec3(-1, 0, 0), arch));
  const auto angle = [&](const Vec3& h) { return h.z() < z_share(0.3) && h.y() > y_share(0.25); };
  add("go_L", best_of(skull.positions, Vec3(0.4, 0.65, -0.65).normalized(), angle));
  add("go_R", best_of(skull.positions, Vec3(-0.4, 0.65, -0.65).normalized(), angle));
  // Refined until the points stop moving, so that each is a local extremum of its definition (a region's boundary
  // may have cut a slope).
  LandmarkSet located = refine_landmarks(skull, frame, rough);
  for (int round = 0; round < 10; ++round) {
    LandmarkSet next = refine_landmarks(skull, frame, located);
    bool moved = false;
    for (std::size_t i = 0; i < next.size(); ++i) moved = moved || next[i].position_mm != located[i].position_mm;
    located = std::move(next);
    if (!moved) break;
  }
  return located;
}

}  // namespace forensim
