#include "craniofacial/face_evaluation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/ray_caster.hpp"
#include "volume/iso_surface.hpp"

namespace forensim {
namespace {

constexpr double k_default_skin_iso_hu = -524.0;  // 500 in HU + 1024 storage (VTK medical examples)
constexpr double k_hu_storage_offset = 1024.0;

Vec3 landmark(const LandmarkSet& set, const char* name) {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  for (const Landmark& l : set.landmarks()) {
    const auto ref = vocabulary.find(l.name);
    if (ref && vocabulary.name(*ref) == name) return l.position_mm;
  }
  throw InputError("face region", name, "the skull landmarks lack it (needed for the face region)");
}

}  // namespace

TriMesh real_face_surface(const ScalarGrid& volume, const std::string& source, const RealFaceOptions& options,
                          double* iso_used) {
  volume.validate(source);
  double iso = 0.0;
  if (options.skin_iso_value) {
    iso = *options.skin_iso_value;
    if (!std::isfinite(iso)) throw InputError(source, "skin iso-value", "is not finite");
  } else {
    const auto range = volume.value_range();
    iso = k_default_skin_iso_hu + (range.first >= -100.0f ? k_hu_storage_offset : 0.0);
  }
  IsoSurfaceOptions iso_options;
  iso_options.keep_largest_components = 1;
  iso_options.smoothing_iterations = options.smoothing_iterations;
  TriMesh skin = extract_iso_surface(volume, iso, iso_options);
  if (skin.triangles.empty()) {
    throw InputError(source, fmt::format("iso-value {}", iso), "no voxel lies above the skin iso-value");
  }
  if (iso_used) *iso_used = iso;
  return skin;
}

bool FaceRegion::contains(const Vec3& p) const {
  return coronal.signed_distance(p) <= 0.0 && forehead.signed_distance(p) <= 0.0 && jaw.signed_distance(p) <= 0.0;
}

FaceRegion face_region(const LandmarkSet& skull_landmarks, const HeadFrame& frame, const FaceRegionOptions& options) {
  const Vec3 g = landmark(skull_landmarks, "g");
  const Vec3 me = landmark(skull_landmarks, "me");
  const Vec3 go_l = landmark(skull_landmarks, "go_L");
  const Vec3 go_r = landmark(skull_landmarks, "go_R");
  const Vec3 superior = frame.axes.col(2).normalized();
  const Vec3 posterior = frame.axes.col(1).normalized();
  FaceRegion region;
  region.coronal = Plane{0.5 * (go_l + go_r) + options.ear_margin_mm * posterior, posterior};
  region.forehead = Plane{g + options.forehead_mm * superior, superior};
  Vec3 n = (go_l - me).cross(go_r - me);
  require_input(n.norm() > 1e-9, "face region", "me", "menton and the gonia are collinear");
  n.normalize();
  if (n.dot(superior) > 0.0) n = -n;
  region.jaw = Plane{me + options.chin_margin_mm * n, n};
  return region;
}

nlohmann::json FaceEvaluation::to_json() const {
  return {{"mean_abs_mm", mean_abs_mm},
          {"rms_mm", rms_mm},
          {"signed_mean_mm", signed_mean_mm},
          {"within_share", within_share},
          {"within_percent", 100.0 * within_share},
          {"within_mm", within_mm},
          {"max_abs_mm", max_abs_mm},
          {"p90_abs_mm", p90_abs_mm},
          {"area_mm2", area_mm2},
          {"vertex_count", vertex_count}};
}

FaceEvaluation evaluate_face(const TriMesh& real_skin, const TriMesh& reconstructed_skin, const FaceRegion& region,
                             const ScanFieldOfView& view, const FaceEvaluationOptions& options) {
  require_input(!real_skin.triangles.empty(), "real face", "", "the mesh has no triangles");
  require_input(!reconstructed_skin.triangles.empty(), "reconstructed skin", "", "the mesh has no triangles");
  require_input(options.within_mm > 0.0, "face evaluation", "within_mm", "must be positive");
  real_skin.validate("real face");
  reconstructed_skin.validate("reconstructed skin");
  const std::size_t nv = real_skin.positions.size();
  const std::size_t nt = real_skin.triangles.size();
  const std::vector<Vec3> normals = vertex_normals(real_skin);

  // Exterior vertices: a ray along the normal leaves the skin.
  const RayCaster caster(real_skin);
  std::vector<char> exterior(nv, 0);
  parallel_for(0, nv, [&](std::size_t i) {
    if (normals[i].squaredNorm() == 0.0) return;
    exterior[i] =
        static_cast<char>(!caster.occluded(real_skin.positions[i], normals[i], options.exterior_ray_offset_mm));
  });
  // Triangles in the region, their area shared among their vertices.
  const std::vector<char> cap = view.cap_triangles(real_skin);
  std::vector<double> weight(nv, 0.0);
  std::vector<char> measured_triangle(nt, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    const Tri& f = real_skin.triangles[t];
    const Vec3& a = real_skin.positions[f[0]];
    const Vec3& b = real_skin.positions[f[1]];
    const Vec3& c = real_skin.positions[f[2]];
    if (cap[t] || !region.contains((a + b + c) / 3.0)) continue;
    if (!exterior[f[0]] && !exterior[f[1]] && !exterior[f[2]]) continue;
    measured_triangle[t] = 1;
    const double third = triangle_area(a, b, c) / 3.0;
    for (Index v : f) weight[static_cast<std::size_t>(v)] += third;
  }
  std::vector<std::size_t> measured;
  for (std::size_t i = 0; i < nv; ++i) {
    if (weight[i] > 0.0) measured.push_back(i);
  }
  require_input(!measured.empty(), "face region", "", "no area of the real face lies in it");

  // Signed distances to the reconstructed skin.
  const ClosestPointQuery query(reconstructed_skin);
  const std::vector<Vec3> recon_normals = vertex_normals(reconstructed_skin);
  FaceEvaluation e;
  e.within_mm = options.within_mm;
  e.vertex_distance_mm.assign(nv, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> d(measured.size());
  parallel_for(0, measured.size(), [&](std::size_t k) {
    const Vec3& p = real_skin.positions[measured[k]];
    const auto hit = query.query(p);
    const Tri& f = reconstructed_skin.triangles[static_cast<std::size_t>(hit->triangle)];
    const Vec3 n = hit->barycentric[0] * recon_normals[f[0]] + hit->barycentric[1] * recon_normals[f[1]] +
                   hit->barycentric[2] * recon_normals[f[2]];
    d[k] = (p - hit->point).dot(n) >= 0.0 ? hit->distance : -hit->distance;
  });
  // Area-weighted figures, summed in vertex order (the same at any thread count).
  double area = 0.0, sum_abs = 0.0, sum_sq = 0.0, sum_signed = 0.0, within = 0.0;
  std::vector<std::pair<double, double>> by_size(measured.size());
  for (std::size_t k = 0; k < measured.size(); ++k) {
    const double w = weight[measured[k]];
    const double a = std::abs(d[k]);
    area += w;
    sum_abs += w * a;
    sum_sq += w * d[k] * d[k];
    sum_signed += w * d[k];
    if (a <= options.within_mm) within += w;
    e.max_abs_mm = std::max(e.max_abs_mm, a);
    e.vertex_distance_mm[measured[k]] = d[k];
    by_size[k] = {a, w};
  }
  e.area_mm2 = area;
  e.vertex_count = measured.size();
  e.mean_abs_mm = sum_abs / area;
  e.rms_mm = std::sqrt(sum_sq / area);
  e.signed_mean_mm = sum_signed / area;
  e.within_share = within / area;
  std::sort(by_size.begin(), by_size.end());
  double acc = 0.0;
  for (const auto& [a, w] : by_size) {
    acc += w;
    e.p90_abs_mm = a;
    if (acc >= 0.9 * area) break;
  }
  // The measured part of the real face with its distances.
  std::vector<bool> keep(nt);
  for (std::size_t t = 0; t < nt; ++t) keep[t] = measured_triangle[t] != 0;
  TriMesh with_field = real_skin;
  std::vector<double> field(nv);
  for (std::size_t i = 0; i < nv; ++i)
    field[i] = std::isfinite(e.vertex_distance_mm[i]) ? e.vertex_distance_mm[i] : 0.0;
  with_field.vertex_fields.scalars["distance"] = field;
  e.face = extract_triangles(with_field, keep);
  return e;
}

}  // namespace forensim
