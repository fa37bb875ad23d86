#include "spatial/ray_caster.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "spatial/embree_scene.hpp"

namespace forensim {
namespace {

/// Intersect context carrying the culling mode to the filter callback (the Embree context comes first so
/// the callback can recover this struct from the pointer Embree hands it).
struct CullingContext {
  RTCIntersectContext base;
  FaceCulling culling;
  const Vec3* face_normals;
};

void culling_filter(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const CullingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const Vec3 direction(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                         RTCRayN_dir_z(args->ray, args->N, i));
    const double s = direction.dot(context->face_normals[prim]);
    if ((context->culling == FaceCulling::back && s > 0.0) || (context->culling == FaceCulling::front && s < 0.0)) {
      args->valid[i] = 0;
    }
  }
}

void check_ray(const Vec3& origin, const Vec3& direction, double t_min, double t_max) {
  require_input(origin.allFinite(), "ray", "origin", "origin is not finite");
  require_input(direction.allFinite() && direction.squaredNorm() > 0.0, "ray", "direction",
                "direction is zero or not finite");
  require_input(t_min >= 0.0 && t_max >= t_min, "ray", "t range",
                "needs 0 <= t_min <= t_max, got [" + std::to_string(t_min) + ", " + std::to_string(t_max) + "]");
}

}  // namespace

bool ray_triangle_intersect(const Vec3& origin, const Vec3& direction, const Vec3& a, const Vec3& b, const Vec3& c,
                            double t_min, double t_max, double& t, Vec3& barycentric) {
  const Vec3 e1 = b - a;
  const Vec3 e2 = c - a;
  const Vec3 p = direction.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0 || !std::isfinite(det)) return false;
  const double inv = 1.0 / det;
  const Vec3 s = origin - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 q = s.cross(e1);
  const double v = direction.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  const double tt = e2.dot(q) * inv;
  if (tt < t_min || tt > t_max) return false;
  t = tt;
  barycentric = Vec3(1.0 - u - v, u, v);
  return true;
}

std::optional<RayHit> intersect_ray(const TriMesh& mesh, const Vec3& origin, const Vec3& direction, double t_min,
                                    double t_max, FaceCulling culling) {
  check_ray(origin, direction, t_min, t_max);
  std::optional<RayHit> best;
  double t_best = t_max;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& tri = mesh.triangles[f];
    const Vec3& a = mesh.positions[tri[0]];
    const Vec3& b = mesh.positions[tri[1]];
    const Vec3& c = mesh.positions[tri[2]];
    const Vec3 n = (b - a).cross(c - a);
    const double s = direction.dot(n);
    if ((culling == FaceCulling::back && s > 0.0) || (culling == FaceCulling::front && s < 0.0)) continue;
    double t = 0.0;
    Vec3 bary;
    if (!ray_triangle_intersect(origin, direction, a, b, c, t_min, t_best, t, bary)) continue;
    if (best && t >= best->t) continue;
    RayHit hit;
    hit.triangle = static_cast<Index>(f);
    hit.barycentric = bary;
    // Embree accepted the hit in float within [t_min, t_max]; the double t keeps to that range (a ray starting on
    // the surface would otherwise report a t a rounding error below t_min).
    hit.t = std::clamp(t, t_min, t_max);
    hit.point = bary[0] * a + bary[1] * b + bary[2] * c;
    const double n_norm = n.norm();
    hit.normal = n_norm > 0.0 ? Vec3(n / n_norm) : Vec3::Zero();
    best = hit;
    t_best = t;
  }
  return best;
}

struct RayCaster::Impl {
  explicit Impl(const TriMesh& mesh) : scene(mesh, "ray caster mesh", true) {
    face_normals.reserve(scene.triangles().size());
    for (const Tri& t : scene.triangles()) {
      const Vec3& a = scene.positions()[t[0]];
      face_normals.push_back((scene.positions()[t[1]] - a).cross(scene.positions()[t[2]] - a));
    }
  }

  void init_context(CullingContext& context, FaceCulling culling) const {
    rtcInitIntersectContext(&context.base);
    context.culling = culling;
    context.face_normals = face_normals.data();
    if (culling != FaceCulling::none) context.base.filter = culling_filter;
  }

  static void fill_ray(RTCRay& ray, const Vec3& origin, const Vec3& direction, double t_min, double t_max,
                       const Vec3& shift) {
    const Vec3 o = origin - shift;
    ray.org_x = static_cast<float>(o.x());
    ray.org_y = static_cast<float>(o.y());
    ray.org_z = static_cast<float>(o.z());
    ray.dir_x = static_cast<float>(direction.x());
    ray.dir_y = static_cast<float>(direction.y());
    ray.dir_z = static_cast<float>(direction.z());
    ray.tnear = static_cast<float>(t_min);
    ray.tfar = std::isinf(t_max) ? std::numeric_limits<float>::infinity() : static_cast<float>(t_max);
    ray.time = 0.0f;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
  }

  std::optional<RayHit> intersect(const Vec3& origin, const Vec3& direction, double t_min, double t_max,
                                  FaceCulling culling) const {
    if (scene.empty()) return std::nullopt;
    CullingContext context;
    init_context(context, culling);
    RTCRayHit rayhit;
    fill_ray(rayhit.ray, origin, direction, t_min, t_max, scene.shift());
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene.scene(), &context.base, &rayhit);
    if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    RayHit hit;
    hit.triangle = static_cast<Index>(rayhit.hit.primID);
    const Tri& tri = scene.triangles()[rayhit.hit.primID];
    const Vec3& a = scene.positions()[tri[0]];
    const Vec3& b = scene.positions()[tri[1]];
    const Vec3& c = scene.positions()[tri[2]];
    // Refine in double against the plane of the triangle Embree found (no inside test: Embree already
    // decided which triangle, and for a hit on a shared edge the double result may fall just outside).
    const Vec3 e1 = b - a;
    const Vec3 e2 = c - a;
    const Vec3 p = direction.cross(e2);
    const double det = e1.dot(p);
    double u = rayhit.hit.u;
    double v = rayhit.hit.v;
    double t = rayhit.ray.tfar;
    if (std::abs(det) > 1e-12 * e1.norm() * e2.norm() * direction.norm()) {
      const double inv = 1.0 / det;
      const Vec3 s = origin - a;
      const Vec3 q = s.cross(e1);
      u = s.dot(p) * inv;
      v = direction.dot(q) * inv;
      t = e2.dot(q) * inv;
    }
    Vec3 bary(1.0 - u - v, u, v);
    if ((bary.array() < 0.0).any()) {
      bary = bary.cwiseMax(0.0);
      const double sum = bary.sum();
      bary = sum > 0.0 ? Vec3(bary / sum) : Vec3(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
    }
    hit.barycentric = bary;
    // Embree accepted the hit in float within [t_min, t_max]; the double t keeps to that range (a ray starting on
    // the surface would otherwise report a t a rounding error below t_min).
    hit.t = std::clamp(t, t_min, t_max);
    hit.point = bary[0] * a + bary[1] * b + bary[2] * c;
    const Vec3 n = e1.cross(e2);
    const double n_norm = n.norm();
    hit.normal = n_norm > 0.0 ? Vec3(n / n_norm) : Vec3::Zero();
    return hit;
  }

  bool occluded(const Vec3& origin, const Vec3& direction, double t_min, double t_max, FaceCulling culling) const {
    if (scene.empty()) return false;
    CullingContext context;
    init_context(context, culling);
    RTCRay ray;
    fill_ray(ray, origin, direction, t_min, t_max, scene.shift());
    rtcOccluded1(scene.scene(), &context.base, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
  }

  EmbreeScene scene;
  std::vector<Vec3> face_normals;  ///< unnormalised, counter-clockwise; only their sign against rays matters
};

RayCaster::RayCaster(const TriMesh& mesh) : m_impl(std::make_unique<Impl>(mesh)) {}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

std::size_t RayCaster::triangle_count() const {
  return m_impl->scene.triangles().size();
}

std::optional<RayHit> RayCaster::intersect(const Vec3& origin, const Vec3& direction, double t_min, double t_max,
                                           FaceCulling culling) const {
  check_ray(origin, direction, t_min, t_max);
  return m_impl->intersect(origin, direction, t_min, t_max, culling);
}

std::vector<std::optional<RayHit>> RayCaster::intersect_batch(const std::vector<Vec3>& origins,
                                                              const std::vector<Vec3>& directions, double t_min,
                                                              double t_max, FaceCulling culling) const {
  require_input(origins.size() == directions.size(), "ray batch", "",
                std::to_string(origins.size()) + " origins but " + std::to_string(directions.size()) + " directions");
  for (std::size_t i = 0; i < origins.size(); ++i) {
    try {
      check_ray(origins[i], directions[i], t_min, t_max);
    } catch (const InputError& e) {
      throw InputError("ray batch", "ray " + std::to_string(i), e.problem());
    }
  }
  std::vector<std::optional<RayHit>> hits(origins.size());
  parallel_for(
      0, origins.size(),
      [&](std::size_t i) { hits[i] = m_impl->intersect(origins[i], directions[i], t_min, t_max, culling); }, 64);
  return hits;
}

bool RayCaster::occluded(const Vec3& origin, const Vec3& direction, double t_min, double t_max,
                         FaceCulling culling) const {
  check_ray(origin, direction, t_min, t_max);
  return m_impl->occluded(origin, direction, t_min, t_max, culling);
}

}  // namespace forensim
