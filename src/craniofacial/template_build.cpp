#include "craniofacial/template_build.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "craniofacial/rbf_warp.hpp"
#include "craniofacial/skull_normals.hpp"
#include "craniofacial/skull_registration.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/vertex_neighbours.hpp"
#include "image/png_io.hpp"
#include "mesh_processing/uv_atlas.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/ray_caster.hpp"
#include "texture/uv_bake.hpp"

namespace forensim {

namespace {

/// The rotation and translation taking `from` onto `to` in the least-squares sense, no scale (Kabsch 1976):
/// the subject keeps its size and is only placed in the template's frame.
struct Rigid {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 apply(const Vec3& p) const { return rotation * p + translation; }
};

Rigid kabsch(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  Eigen::Matrix3Xd src(3, static_cast<Eigen::Index>(from.size())), dst(3, static_cast<Eigen::Index>(to.size()));
  for (std::size_t i = 0; i < from.size(); ++i) {
    src.col(static_cast<Eigen::Index>(i)) = from[i];
    dst.col(static_cast<Eigen::Index>(i)) = to[i];
  }
  const Eigen::Matrix4d m = Eigen::umeyama(src, dst, false);  // Umeyama 1991 without its scale: Kabsch
  Rigid r;
  r.rotation = m.topLeftCorner<3, 3>();
  r.translation = m.topRightCorner<3, 1>();
  return r;
}

TriMesh moved(TriMesh mesh, const Rigid& r) {
  for (Vec3& p : mesh.positions) p = r.apply(p);
  for (Vec3& n : mesh.normals) n = r.rotation * n;
  return mesh;
}

/// The skin point a pair measures on a skin: where skull + t * normal first meets it (t in [0, max_t]) on a
/// triangle that is not a cap.
std::optional<RayHit> skin_hit(const RayCaster& rays, const std::vector<char>& caps, const Vec3& skull,
                               const Vec3& normal, double max_t) {
  double t_min = 0.0;
  for (int k = 0; k < 8; ++k) {
    auto hit = rays.intersect(skull, normal, t_min, max_t);
    if (!hit) return std::nullopt;
    if (caps.empty() || !caps[static_cast<std::size_t>(hit->triangle)]) return hit;
    t_min = hit->t + 1e-6;
  }
  return std::nullopt;
}

/// The direction a depth is measured along: the skull's patch normal, or `reference` (the template's direction)
/// where the patch turns more than 45 degrees from it.
Vec3 measuring_direction(const Vec3& patch, const Vec3& reference) {
  return patch.dot(reference) >= std::cos(M_PI / 4.0) ? patch : reference.normalized();
}

}  // namespace

LandmarkSet skin_landmarks_by_registration(const TemplateHead& base, const TriMesh& head, double* rms_mm) {
  require_input(!head.triangles.empty(), "head mesh", "", "has no triangles");
  SkullRegistrationOptions options;
  options.similarity.scale_prior_sd = 0.0;  // a scan's size is its own: the moments start it
  const SkullRegistration reg = register_skull(base.skin, head, options);
  if (rms_mm) *rms_mm = reg.rms_mm;
  const ClosestPointQuery on_head(head);
  LandmarkSet out("skin landmarks by registration");
  for (const TemplateLandmarkPair& p : base.landmarks) {
    out.add({p.skin_name, on_head.query(reg.map(p.skin))->point, LandmarkSource::detected, 1.0});
  }
  for (const TemplateSkinLandmark& l : base.skin_landmarks) {
    if (!out.contains(l.name))
      out.add({l.name, on_head.query(reg.map(l.position))->point, LandmarkSource::detected, 1.0});
  }
  return out;
}

TemplateBuild build_template_head(const TemplateHead& base, const TemplateBuildInput& input,
                                  const TemplateBuildOptions& options) {
  const std::string source = input.source.empty() ? std::string("template build input") : input.source;
  require_input(!base.skin.triangles.empty() && !base.landmarks.empty(), "template build", "base template",
                "has no skin or no landmarks");
  require_input(!input.skin.triangles.empty(), source, "skin", "has no triangles");
  input.skin.validate(source + " skin");
  if (input.skull) {
    require_input(!input.skull->triangles.empty(), source, "skull", "has no triangles");
    input.skull->validate(source + " skull");
  }
  require_input(options.max_depth_mm > 0.0 && options.max_depth_mm <= 200.0, "template build", "max_depth_mm",
                "must lie in (0, 200] mm");
  require_input(options.conform_reach_mm > 0.0 && options.conform_reach_mm <= 100.0, "template build",
                "conform_reach_mm", "must lie in (0, 100] mm");
  require_input(options.patch_radius_mm >= 0.0 && options.patch_radius_mm <= 50.0, "template build", "patch_radius_mm",
                "must lie in [0, 50] mm");
  require_input(options.texture_size >= 16 && options.texture_size <= 8192, "template build", "texture_size",
                "must lie in [16, 8192]");
  require_input(input.texture.empty() || input.skin.has_uvs(), source, "texture",
                "is given but the skin mesh has no texture coordinates");

  TemplateBuild out;
  TemplateBuildReport& report = out.report;
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const std::vector<char> caps = input.skin_view.cap_triangles(input.skin);

  // 1. Correspondences in the subject's frame: template point -> subject point, skull landmarks and skin points.
  std::optional<SkullSurface> subject_skull;
  if (input.skull) subject_skull.emplace(*input.skull);
  const RayCaster subject_skin_rays(input.skin);
  const SkullSurface base_skull(base.skull);
  const RayCaster base_skin_rays(base.skin);
  struct Measured {
    bool on_skull = false;
    Vec3 skull = Vec3::Zero(), normal = Vec3::Zero();
  };
  std::vector<Measured> measured(base.landmarks.size());
  std::vector<Vec3> from, to;
  // The skull landmarks first: they turn the template's directions into the subject's frame (a rigid fit).
  std::vector<std::string> bone_of(base.landmarks.size());
  std::vector<Vec3> bone_from, bone_to;
  for (std::size_t i = 0; i < base.landmarks.size(); ++i) {
    const TemplateLandmarkPair& pair = base.landmarks[i];
    const LandmarkRef skin_ref = vocabulary.resolve(pair.skin_name, "template head", pair.skin_name);
    const auto bone_ref = vocabulary.paired(skin_ref);
    bone_of[i] = bone_ref ? vocabulary.name(*bone_ref) : pair.bone_name;
    if (!subject_skull) continue;
    const Landmark* on_bone = input.skull_landmarks.find(bone_of[i]);
    if (on_bone == nullptr) continue;
    const ClosestPoint at = subject_skull->closest_point(on_bone->position_mm);
    measured[i].on_skull = true;
    measured[i].skull = at.point;
    measured[i].normal = subject_skull->patch_normal(at, options.patch_radius_mm);
    bone_from.push_back(pair.skull);
    bone_to.push_back(at.point);
  }
  const Mat3 to_subject = bone_from.size() >= 3 ? kabsch(bone_from, bone_to).rotation : Mat3::Identity();
  for (std::size_t i = 0; i < base.landmarks.size(); ++i) {
    const TemplateLandmarkPair& pair = base.landmarks[i];
    if (const Landmark* given = input.skin_landmarks.find(pair.skin_name)) {
      from.push_back(pair.skin);
      to.push_back(given->position_mm);
      report.pairs_from_skin.push_back(pair.skin_name);
      continue;
    }
    if (!measured[i].on_skull) continue;
    Measured& m = measured[i];
    // Both skin points measured the same way: along the skull's patch normal, or the template's direction where the
    // patch turns more than 45 degrees from it (teeth and thin nasal bones tilt a patch), so the two correspond.
    const Vec3 base_patch = base_skull.patch_normal(base_skull.closest_point(pair.skull), options.patch_radius_mm);
    const Vec3 base_normal = measuring_direction(base_patch, pair.skull_normal);
    m.normal = measuring_direction(m.normal, to_subject * base_normal);
    const auto base_hit = skin_hit(base_skin_rays, {}, pair.skull, base_normal, options.max_depth_mm);
    if (!base_hit) {
      report.pairs_left.emplace_back(pair.skin_name, "the template's own skull normal there meets no skin");
      continue;
    }
    const auto hit = skin_hit(subject_skin_rays, caps, m.skull, m.normal, options.max_depth_mm);
    if (hit && (!input.skin_view.bounded() || input.skin_view.contains(hit->point, input.skin_view.max_spacing_mm()))) {
      from.push_back(base_hit->point);
      to.push_back(hit->point);
      report.pairs_from_skull.push_back(pair.skin_name);
    } else if (input.skin_view.bounded() && !input.skin_view.contains(m.skull + base_hit->t * m.normal)) {
      // The skin there was not scanned (a CT's vault): the template's own depth along the subject's normal, so
      // that the skin follows the (completed) skull instead of the warp's extrapolation.
      from.push_back(base_hit->point);
      to.push_back(m.skull + base_hit->t * m.normal);
      report.pairs_unscanned.push_back(pair.skin_name);
    } else {
      report.pairs_left.emplace_back(pair.skin_name, fmt::format("the skull normal at {} meets no skin within {} mm",
                                                                 bone_of[i], options.max_depth_mm));
    }
  }
  for (const Landmark& l : input.skin_landmarks.landmarks()) {
    for (const TemplateSkinLandmark& s : base.skin_landmarks) {
      if (s.name != l.name) continue;
      from.push_back(s.position);
      to.push_back(l.position_mm);
      report.pairs_from_skin.push_back(s.name);
    }
  }
  require_input(from.size() >= 4, source, "landmarks",
                fmt::format("only {} skin points of the subject pair with the template's (at least 4 needed: skull "
                            "landmarks on a skull whose normals meet the skin, or skin landmarks named as the "
                            "template's, e.g. se', prn', pg')",
                            from.size()));
  report.warp_landmarks = from.size();

  // The subject placed in the template's frame (rigid: it keeps its size).
  const Rigid place = kabsch(to, from);
  for (Vec3& p : to) p = place.apply(p);
  for (Measured& m : measured) {
    m.skull = place.apply(m.skull);
    m.normal = place.rotation * m.normal;
  }
  const TriMesh skin = moved(input.skin, place);
  const std::optional<TriMesh> skull = input.skull ? std::optional(moved(*input.skull, place)) : std::nullopt;

  // 2. The warp of the template onto the subject (eq. 1).
  const RbfWarp warp(from, to, source + " landmarks");
  TemplateHead& head = out.head;
  head = base;
  head.source = source;
  head.texture_png.clear();
  const std::vector<Vec3> warped = warp.evaluate_batch(base.skin.positions);
  TriMesh warped_skin = base.skin;
  warped_skin.positions = warped;
  warped_skin.normals = vertex_normals(warped_skin);

  // 3. The warped skin onto the subject's (placed) in rounds: each vertex along its normal to the nearest facing
  // hit; the displacements of the vertices without one (the vault a CT did not scan, folds) filled in smoothly
  // from their neighbours' (a harmonic extension), so the skin stays whole; then again from there.
  const RayCaster placed_skin_rays(skin);
  const Rigid unplace{place.rotation.transpose(), -(place.rotation.transpose() * place.translation)};
  const double sample_mm = input.skin_view.bounded() ? input.skin_view.max_spacing_mm() : 0.0;
  const auto placed_view_contains = [&](const Vec3& p) {
    return input.skin_view.contains(unplace.apply(p), sample_mm);
  };
  const std::size_t nv = warped.size();
  const VertexNeighbours adjacency = vertex_neighbours(base.skin.triangles, nv);
  const auto neighbour_mean = [&](const std::vector<Vec3>& values, std::size_t v) {
    Vec3 sum = Vec3::Zero();
    for (std::size_t k = adjacency.start[v]; k < adjacency.start[v + 1]; ++k) {
      sum += values[static_cast<std::size_t>(adjacency.index[k])];
    }
    return Vec3(sum / static_cast<double>(adjacency.degree(v)));
  };
  std::vector<Vec3> conformed = warped;
  std::vector<char> moved_flag(nv, 0);
  const auto conform_round = [&](bool last) {
    TriMesh current = warped_skin;
    current.positions = conformed;
    const std::vector<Vec3> normals = vertex_normals(current);
    std::vector<Vec3> shift(nv, Vec3::Zero());
    std::fill(moved_flag.begin(), moved_flag.end(), 0);
    parallel_for(
        0, nv,
        [&](std::size_t v) {
          const Vec3& p = conformed[v];
          const Vec3& n = normals[v];
          if (!(n.squaredNorm() > 0.5)) return;
          std::optional<RayHit> best;
          double best_t = options.conform_reach_mm;
          for (const double sign : {1.0, -1.0}) {
            if (best && best_t <= 0.0) break;
            double t_min = 0.0;
            for (int k = 0; k < 6; ++k) {
              const auto hit = placed_skin_rays.intersect(p, sign * n, t_min, best_t);
              if (!hit) break;
              // Not a cap, nor the rim of the skin where the scan's cut flares it (within a sample of the cut).
              const bool cap = !caps.empty() && caps[static_cast<std::size_t>(hit->triangle)];
              const bool rim = input.skin_view.bounded() && !placed_view_contains(hit->point);
              if (!cap && !rim && hit->normal.dot(n) > 0.3) {
                best = hit;
                best_t = hit->t;
                break;
              }
              t_min = hit->t + 1e-6;
            }
          }
          if (best) {
            shift[v] = best->point - p;
            moved_flag[v] = 1;
          }
        },
        256);
    // A hit that disagrees with most of its neighbours' by more than 3 mm is a stray (the far wall of a nostril,
    // an object in the scan): dropped, so that the extension fills it in.
    std::vector<char> keep = moved_flag;
    for (std::size_t v = 0; v < nv; ++v) {
      if (!moved_flag[v]) continue;
      std::size_t hits = 0, far = 0;
      for (std::size_t k = adjacency.start[v]; k < adjacency.start[v + 1]; ++k) {
        const auto u = static_cast<std::size_t>(adjacency.index[k]);
        if (!moved_flag[u]) continue;
        ++hits;
        if ((shift[u] - shift[v]).norm() > 3.0) ++far;
      }
      if (hits > 0 && 2 * far > hits) keep[v] = 0;
    }
    for (std::size_t v = 0; v < nv; ++v) {
      if (moved_flag[v] && !keep[v]) shift[v] = Vec3::Zero();
    }
    moved_flag = std::move(keep);
    // Harmonic extension (Gauss-Seidel in vertex order: deterministic) until no shift changes by more than
    // 1e-4 mm in a sweep (at most 400), then, before the last round, a light smoothing of every shift so that
    // single stray hits do not tear the skin.
    for (int sweep = 0; sweep < 400; ++sweep) {
      double change = 0.0;
      for (std::size_t v = 0; v < nv; ++v) {
        if (moved_flag[v] || adjacency.degree(v) == 0) continue;
        const Vec3 next = neighbour_mean(shift, v);
        change = std::max(change, (next - shift[v]).squaredNorm());
        shift[v] = next;
      }
      if (change < 1e-8) break;
    }
    if (!last) {
      for (int sweep = 0; sweep < 3; ++sweep) {
        std::vector<Vec3> smoothed = shift;
        for (std::size_t v = 0; v < nv; ++v) {
          if (adjacency.degree(v) > 0) smoothed[v] = 0.5 * shift[v] + 0.5 * neighbour_mean(shift, v);
        }
        shift = std::move(smoothed);
      }
    }
    for (std::size_t v = 0; v < nv; ++v) conformed[v] += shift[v];
  };
  for (int round = 0; round < 6; ++round) conform_round(round == 5);
  // Triangles turned over against the warped skin (a fold on a lip, an ear's rim): their corners take the mean of
  // their neighbours' positions.
  const std::vector<Vec3> warped_face_normal = face_normals(warped_skin);
  for (int round = 0; round < 20; ++round) {
    TriMesh probe = warped_skin;
    probe.positions = conformed;
    const std::vector<Vec3> fn = face_normals(probe);
    std::size_t flipped = 0;
    std::vector<char> fix(nv, 0);
    for (std::size_t f = 0; f < fn.size(); ++f) {
      if (fn[f].dot(warped_face_normal[f]) >= 0.0) continue;
      ++flipped;
      for (const Index vi : probe.triangles[f]) fix[static_cast<std::size_t>(vi)] = 1;
    }
    report.flipped_triangles = flipped;
    if (flipped == 0 || round == 19) break;
    const std::vector<Vec3> before = conformed;
    for (std::size_t v = 0; v < nv; ++v) {
      if (!fix[v] || adjacency.degree(v) == 0) continue;
      conformed[v] = neighbour_mean(before, v);
      moved_flag[v] = 0;
    }
  }
  double moved_sum = 0.0;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!moved_flag[v]) continue;
    ++report.vertices_conformed;
    moved_sum += (conformed[v] - warped[v]).norm();
  }
  report.vertices_warped = nv - report.vertices_conformed;
  report.mean_conform_mm = report.vertices_conformed ? moved_sum / static_cast<double>(report.vertices_conformed) : 0;
  head.skin.positions = conformed;
  head.skin.normals = vertex_normals(head.skin);
  if (head.skin.has_uvs()) head.uv_l2_stretch = uv_l2_stretch(head.skin);

  // Each pair's template direction carried by the warp: which side of the bone is outward there.
  std::vector<Vec3> carried(base.landmarks.size());
  for (std::size_t i = 0; i < base.landmarks.size(); ++i) {
    const TemplateLandmarkPair& pair = base.landmarks[i];
    carried[i] = (warp.evaluate(pair.skull + pair.skull_normal) - warp.evaluate(pair.skull)).normalized();
  }

  // The skull: the subject's, or the template's placed under the skin (its pairs then hold by construction).
  struct PlacedPair {
    bool placed = false;
    Vec3 skull = Vec3::Zero(), skin = Vec3::Zero();
  };
  std::vector<PlacedPair> placed_pair(base.landmarks.size());
  if (skull) {
    head.skull = *skull;
  } else {
    // No skull: the template's, placed under the new skin at the template's own tissue depths: each pair's skull
    // point goes to its skin point less its depth along the carried normal, and the RBF warp of eq. 1 on those
    // points carries the whole skull (the skin's warp alone would leave it wherever the skin's shape puts it).
    const ClosestPointQuery on_new_skin(head.skin);
    std::vector<Vec3> skull_from, skull_to;
    for (std::size_t i = 0; i < base.landmarks.size(); ++i) {
      const TemplateLandmarkPair& pair = base.landmarks[i];
      if (!input.skin_landmarks.contains(pair.skin_name)) continue;
      const Vec3 q = on_new_skin.query(warp.evaluate(pair.skin))->point;
      skull_from.push_back(pair.skull);
      skull_to.push_back(q - pair.depth_mm * carried[i]);
      placed_pair[i] = {true, skull_to.back(), q};
    }
    if (skull_from.size() >= 4) {
      const RbfWarp skull_warp(skull_from, skull_to, source + " skull under the skin");
      head.skull.positions = skull_warp.evaluate_batch(base.skull.positions);
      report.skull_at_template_depths = true;
    } else {
      head.skull.positions = warp.evaluate_batch(base.skull.positions);
      for (PlacedPair& p : placed_pair) p.placed = false;
    }
  }
  head.skull.normals = vertex_normals(head.skull);

  // 4. The pairs on the new skin and skull.
  const RayCaster new_skin_rays(head.skin);
  const ClosestPointQuery new_skin_points(head.skin);
  const SkullSurface new_skull(head.skull);
  for (std::size_t i = 0; i < head.landmarks.size(); ++i) {
    TemplateLandmarkPair& pair = head.landmarks[i];
    if (placed_pair[i].placed) {
      // The skull placed at this pair's own depth under its given skin point: the pair is those two points (a
      // ray along the new skull's patch normal would meet a fold of the skin elsewhere: subnasale, the lips).
      pair.skull = placed_pair[i].skull;
      pair.skin = placed_pair[i].skin;
      pair.depth_mm = (pair.skin - pair.skull).norm();
      const Vec3 along = pair.skin - pair.skull;
      pair.skull_normal = along.norm() > 1e-9 ? Vec3(along / along.norm()) : carried[i];
      continue;
    }
    if (measured[i].on_skull) {
      pair.skull = measured[i].skull;
      pair.skull_normal = measuring_direction(measured[i].normal, carried[i]);
    } else {
      const ClosestPoint at = new_skull.closest_point(warp.evaluate(pair.skull));
      pair.skull = at.point;
      pair.skull_normal = measuring_direction(new_skull.patch_normal(at, options.patch_radius_mm), carried[i]);
    }
    const auto hit = new_skin_rays.intersect(pair.skull, pair.skull_normal, 0.0, options.max_depth_mm);
    if (hit) {
      pair.skin = hit->point;
      pair.depth_mm = hit->t;
    } else {
      pair.skin = new_skin_points.query(warp.evaluate(base.landmarks[i].skin))->point;
      pair.depth_mm = (pair.skin - pair.skull).norm();
      report.pairs_left.emplace_back(pair.skin_name,
                                     "its skull normal misses the new skin: the closest skin point "
                                     "to the warped template's is used");
    }
  }
  for (TemplateSkinLandmark& l : head.skin_landmarks) {
    const Landmark* given = input.skin_landmarks.find(l.name);
    const Vec3 p = given ? place.apply(given->position_mm) : warp.evaluate(l.position);
    l.position = new_skin_points.query(p)->point;
  }
  for (MuscleLayout& m : head.muscles) {
    const std::vector<Vec3> grid = warp.evaluate_batch(m.grid);
    for (std::size_t k = 0; k < grid.size(); ++k) m.grid[k] = new_skin_points.query(grid[k])->point;
  }

  // 5. The subject's texture on the template's atlas.
  if (!input.texture.empty() && head.skin.has_uvs()) {
    const ClosestPointQuery subject_points(skin);
    const UvRaster raster = rasterize_uv(head.skin, options.texture_size, options.texture_size, 2);
    const Image& texture = input.texture;
    Image baked = bake(
        raster, 3,
        [&](const UvTexel& t) {
          const auto cp = subject_points.query(t.position);
          if (!cp) return Vec4f(0.5f, 0.5f, 0.5f, 1.0f);
          return texture.sample_uv(uv_at(skin, cp->triangle, cp->barycentric));
        },
        8, Vec4f(0.5f, 0.5f, 0.5f, 1.0f), texture.encoding());
    head.texture_png = encode_png(baked);
    report.texture_baked = true;
  }
  return out;
}

}  // namespace forensim
