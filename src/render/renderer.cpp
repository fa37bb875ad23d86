#include "render/renderer.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "render/draw.hpp"
#include "render/text.hpp"

namespace forensim {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double infinity = std::numeric_limits<double>::infinity();

// Everything the renderer needs about one object, in world coordinates.
struct PreparedObject {
  const RenderObject* object = nullptr;
  const TriMesh* mesh = nullptr;
  std::vector<Vec3f> positions;       // #V world positions
  std::vector<Vec3f> face_normals;    // #F unit world face normals (counter-clockwise = outward)
  std::vector<Vec3f> corner_normals;  // 3 #F world shading normals (split at creases)
  const std::vector<double>* field = nullptr;
  std::vector<CutPlane> planes;  // removed half-spaces that apply to this object
  bool closed = false;
  bool caps = false;  // draws caps where the scene's cut plane passes through it
};

// Embree filter: rejects hits on the removed side of the object's cut planes (for camera and shadow rays).
void cut_filter(const RTCFilterFunctionNArguments* args) {
  const auto* object = static_cast<const PreparedObject*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3 o(RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                 RTCRayN_org_z(args->ray, args->N, i));
    const Vec3 d(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                 RTCRayN_dir_z(args->ray, args->N, i));
    const Vec3 x = o + static_cast<double>(RTCRayN_tfar(args->ray, args->N, i)) * d;
    for (const CutPlane& plane : object->planes)
      if (plane.signed_distance(x) > 0) args->valid[i] = 0;
  }
}

struct Hit {
  bool valid = false;
  int object = -1;
  unsigned primitive = 0;
  float u = 0, v = 0;
  double t = infinity;
  bool back_facing = false;
  bool cap = false;
};

// Shading inputs at a hit.
struct SurfacePoint {
  Vec3 position;
  Vec3 normal;     // shading normal, facing the viewer side
  Vec3 geometric;  // geometric normal, facing the viewer side
  Vec3f albedo;
  const SurfaceMaterial* material = nullptr;
  double roughness = 0.5;
  double f0 = 0.04;
  bool skin = false;
  bool cap = false;
};

// A light resolved into world coordinates for one camera.
struct WorldLight {
  Light light;
  Vec3 direction, position, edge_u, edge_v;
  double cos_max = 1.0;  // directional: cosine of the angular radius
};

struct LightSample {
  Vec3 wi = Vec3::Zero();
  Vec3f weight = Vec3f::Zero();  // incoming radiance / pdf, without the surface cosine
  double distance = infinity;
  bool valid = false;
};

// Orthonormal basis around unit n (Duff et al. 2017).
void basis(const Vec3& n, Vec3* t, Vec3* b) {
  const double sign = std::copysign(1.0, n[2]);
  const double a = -1.0 / (sign + n[2]);
  const double c = n[0] * n[1] * a;
  *t = Vec3(1.0 + sign * n[0] * n[0] * a, sign * c, -sign * n[0]);
  *b = Vec3(c, sign + n[1] * n[1] * a, -n[1]);
}

Vec3 sample_cone(const Vec3& axis, double cos_max, const Vec2& u) {
  const double cos_t = 1.0 - u[0] * (1.0 - cos_max);
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
  const double phi = 2.0 * pi * u[1];
  Vec3 t, b;
  basis(axis, &t, &b);
  return (std::cos(phi) * sin_t * t + std::sin(phi) * sin_t * b + cos_t * axis).normalized();
}

Vec3 sample_cosine(const Vec3& n, const Vec2& u) {
  const double r = std::sqrt(u[0]), phi = 2.0 * pi * u[1];
  Vec3 t, b;
  basis(n, &t, &b);
  return (r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1.0 - u[0])) * n).normalized();
}

LightSample sample_light(const WorldLight& wl, const Vec3& p, const Vec2& u) {
  LightSample s;
  const Light& l = wl.light;
  const Vec3f emitted = l.colour * static_cast<float>(l.intensity);
  switch (l.kind) {
    case LightKind::directional: {
      s.wi = l.angular_radius_deg > 0 ? sample_cone(wl.direction, wl.cos_max, u) : wl.direction;
      // intensity 1 makes a white Lambertian surface facing the light as bright as its albedo.
      s.weight = emitted * static_cast<float>(pi);
      s.valid = true;
      break;
    }
    case LightKind::sphere: {
      const Vec3 to = wl.position - p;
      const double d2 = to.squaredNorm(), r2 = l.radius * l.radius;
      if (d2 <= r2 * (1 + 1e-9)) break;
      const double d = std::sqrt(d2);
      const double cos_max = std::sqrt(std::max(0.0, 1.0 - r2 / d2));
      s.wi = sample_cone(to / d, cos_max, u);
      const double pdf = 1.0 / (2.0 * pi * std::max(1e-12, 1.0 - cos_max));
      s.weight = emitted / static_cast<float>(pdf);
      const double b = s.wi.dot(to), disc = b * b - (d2 - r2);
      s.distance = disc > 0 ? b - std::sqrt(disc) : d - l.radius;
      s.valid = true;
      break;
    }
    case LightKind::rectangle: {
      const Vec3 q = wl.position + u[0] * wl.edge_u + u[1] * wl.edge_v;
      const Vec3 normal = wl.edge_u.cross(wl.edge_v);
      const double area = normal.norm();
      if (area <= 0) break;
      const Vec3 w = q - p;
      const double dist = w.norm();
      if (dist <= 0) break;
      s.wi = w / dist;
      const double cos_l = -s.wi.dot(normal / area);
      if (cos_l <= 0) break;
      s.weight = emitted * static_cast<float>(cos_l * area / (dist * dist));
      s.distance = dist;
      s.valid = true;
      break;
    }
  }
  return s;
}

// GGX microfacet specular (Walter et al. 2007) with the height-correlated Smith visibility term and
// Schlick's Fresnel; returns f_s (without the cosine).
double ggx_specular(const Vec3& n, const Vec3& v, const Vec3& l, double roughness, double f0) {
  const double ndl = n.dot(l), ndv = std::max(n.dot(v), 1e-4);
  if (ndl <= 0) return 0.0;
  const Vec3 h = (v + l).normalized();
  const double ndh = std::max(n.dot(h), 0.0), vdh = std::max(v.dot(h), 0.0);
  const double a = std::max(roughness * roughness, 1e-3), a2 = a * a;
  const double denom = ndh * ndh * (a2 - 1.0) + 1.0;
  const double d = a2 / (pi * denom * denom);
  const double vis =
      0.5 / (ndl * std::sqrt(ndv * ndv * (1.0 - a2) + a2) + ndv * std::sqrt(ndl * ndl * (1.0 - a2) + a2));
  const double f = f0 + (1.0 - f0) * std::pow(1.0 - vdh, 5.0);
  return d * vis * f;
}

// Per-pixel sample generator: every 2D dimension (the sub-pixel position, each light, the occlusion
// ray) uses the R2 low-discrepancy sequence (Roberts 2018), well stratified for any sample count, with
// a per-pixel random rotation and, for all but the pixel position, a per-pixel random sample order so
// the dimensions are not correlated with each other. Buffers are reused per thread.
class PixelSampler {
 public:
  PixelSampler(std::uint64_t seed, std::uint64_t pixel, int samples, int dimensions)
      : m_samples(samples), m_dimensions(dimensions) {
    RandomStream rng(seed, pixel);
    thread_local std::vector<double> offsets;
    thread_local std::vector<int> order;
    offsets.resize(static_cast<std::size_t>(dimensions + 1) * 2);
    for (double& o : offsets) o = rng.uniform();
    order.resize(static_cast<std::size_t>(dimensions) * static_cast<std::size_t>(samples));
    for (int d = 0; d < dimensions; ++d) {
      int* o = order.data() + static_cast<std::ptrdiff_t>(d) * samples;
      for (int i = 0; i < samples; ++i) o[i] = i;
      for (int i = samples - 1; i > 0; --i) std::swap(o[i], o[rng.uniform_int(0, i)]);
    }
    m_offsets = offsets.data();
    m_order = order.data();
  }
  /// Sub-pixel position of sample s in [0,1)^2.
  Vec2 pixel(int s) const { return r2(s, m_offsets[2 * m_dimensions], m_offsets[2 * m_dimensions + 1]); }
  /// Value of 2D dimension d (0-based) for sample s in [0,1)^2.
  Vec2 get(int d, int s) const {
    if (d >= m_dimensions) d = m_dimensions - 1;
    const int i = m_order[d * m_samples + s];
    return r2(i, m_offsets[2 * d], m_offsets[2 * d + 1]);
  }

 private:
  static Vec2 r2(int i, double ox, double oy) {
    constexpr double a1 = 0.7548776662466927, a2 = 0.5698402909980532;  // 1/g, 1/g^2, g the plastic number
    const double x = 0.5 + a1 * i + ox, y = 0.5 + a2 * i + oy;
    return Vec2(x - std::floor(x), y - std::floor(y));
  }

  int m_samples, m_dimensions;
  const double* m_offsets;
  const int* m_order;
};

}  // namespace

struct Renderer::Impl {
  Scene scene;
  RTCDevice device = nullptr;
  RTCScene rtc = nullptr;
  std::vector<PreparedObject> objects;  // index = Embree geometry id
  bool any_transparent = false;
  bool any_caps = false;
  double scale = 1.0;  // scene diagonal, for ray offsets
  double epsilon = 1e-4;

  ~Impl() {
    if (rtc) rtcReleaseScene(rtc);
    if (device) rtcReleaseDevice(device);
  }

  void prepare(const Scene& source);
  std::vector<WorldLight> resolve_lights(const Camera& camera) const;
  Hit intersect(const Vec3& o, const Vec3& d, double tnear, double tfar) const;
  Hit closest(const Vec3& o, const Vec3& d, double tnear) const;
  float visibility(const Vec3& o, const Vec3& d, double tfar) const;
  SurfacePoint surface(const Hit& hit, const Vec3& o, const Vec3& d) const;
  Vec3f shade(const SurfacePoint& sp, const Vec3& view, const std::vector<WorldLight>& lights,
              const PixelSampler& sampler, int s, bool occlusion) const;
  void trace_pixel(const Camera& camera, const RenderSettings& settings, const std::vector<WorldLight>& lights, int x,
                   int y, Vec3f* colour, float* coverage) const;
  Image render_raw(const Camera& camera, const RenderSettings& settings, Image* coverage_out) const;
  double first_opaque_depth(const Camera& camera, const Ray3& ray) const;
};

void Renderer::Impl::prepare(const Scene& source) {
  scene = source;
  device = rtcNewDevice(nullptr);
  if (!device) throw Error("Embree: cannot create a device");
  rtc = rtcNewScene(device);
  rtcSetSceneFlags(rtc, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(rtc, RTC_BUILD_QUALITY_HIGH);
  const BoundingBox box = scene.bounds();
  scale = box.empty() ? 1.0 : std::max(box.diagonal(), 1e-6);
  epsilon = 2e-5 * scale;
  objects.resize(scene.objects.size());
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    const RenderObject& object = scene.objects[k];
    PreparedObject& p = objects[k];
    p.object = &object;
    p.mesh = object.mesh.get();
    const std::string source_name = "render object '" + object.name + "'";
    require_input(p.mesh != nullptr, source_name, "", "has no mesh");
    const TriMesh& mesh = *p.mesh;
    mesh.validate(source_name);
    const SurfaceMaterial& m = object.material;
    require_input(m.opacity >= 0.0 && m.opacity <= 1.0, source_name, "material", "opacity must be in [0,1]");
    require_input(std::isfinite(m.roughness) && std::isfinite(m.specular) && std::isfinite(m.subsurface), source_name,
                  "material", "non-finite parameter");
    require_input(object.transform.matrix().allFinite() && std::abs(object.transform.linear().determinant()) > 0,
                  source_name, "transform", "must be finite and invertible");
    switch (m.colour_source) {
      case ColourSource::constant:
        break;
      case ColourSource::vertex_colours:
        require_input(mesh.has_colors(), source_name, "material", "vertex colours requested but the mesh has none");
        break;
      case ColourSource::texture:
        require_input(m.base_texture && !m.base_texture->empty(), source_name, "material", "texture is missing");
        require_input(mesh.has_uvs(), source_name, "material", "a texture needs texture coordinates (UVs)");
        break;
      case ColourSource::scalar_field: {
        const auto it = mesh.vertex_fields.scalars.find(m.scalar_field);
        require_input(it != mesh.vertex_fields.scalars.end(), source_name, "material",
                      "no vertex scalar field named '" + m.scalar_field + "'");
        p.field = &it->second;
        break;
      }
    }
    if (m.normal_map)
      require_input(mesh.has_uvs() && !m.normal_map->empty(), source_name, "material",
                    "a normal map needs texture coordinates (UVs)");
    if (m.opacity < 1.0) any_transparent = true;
    if (scene.cutaway && object.use_scene_cutaway) p.planes.push_back(*scene.cutaway);
    if (object.cutaway) p.planes.push_back(*object.cutaway);
    for (const CutPlane& plane : p.planes)
      require_input(plane.normal.allFinite() && plane.normal.norm() > 0 && plane.point.allFinite(), source_name,
                    "cut plane", "needs a finite point and a non-zero normal");
    if (mesh.triangles.empty()) continue;

    p.positions.resize(mesh.vertex_count());
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
      p.positions[i] = (object.transform * mesh.positions[i]).cast<float>();
    const Mat3 normal_matrix = object.transform.linear().inverse().transpose();
    const bool flips = object.transform.linear().determinant() < 0;
    std::vector<Vec3> vertex_normals_world;
    {
      const std::vector<Vec3> source_normals = mesh.has_normals() ? mesh.normals : vertex_normals(mesh);
      vertex_normals_world.resize(source_normals.size());
      for (std::size_t i = 0; i < source_normals.size(); ++i) {
        const Vec3 n = normal_matrix * source_normals[i];
        vertex_normals_world[i] = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
      }
    }
    const double crease_cos = std::cos(std::clamp(m.crease_angle_deg, 0.0, 180.0) * pi / 180.0);
    p.face_normals.resize(mesh.triangle_count());
    p.corner_normals.resize(3 * mesh.triangle_count());
    for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
      const Tri& t = mesh.triangles[f];
      const Vec3 a = p.positions[static_cast<std::size_t>(t[0])].cast<double>();
      const Vec3 b = p.positions[static_cast<std::size_t>(t[1])].cast<double>();
      const Vec3 c = p.positions[static_cast<std::size_t>(t[2])].cast<double>();
      Vec3 fn = (b - a).cross(c - a);
      if (flips) fn = -fn;
      fn = fn.norm() > 0 ? Vec3(fn.normalized()) : Vec3::Zero();
      p.face_normals[f] = fn.cast<float>();
      for (int corner = 0; corner < 3; ++corner) {
        const Vec3& vn = vertex_normals_world[static_cast<std::size_t>(t[static_cast<std::size_t>(corner)])];
        p.corner_normals[3 * f + static_cast<std::size_t>(corner)] = (vn.dot(fn) >= crease_cos ? vn : fn).cast<float>();
      }
    }
    p.closed = check_topology(mesh).is_closed();
    p.caps = p.closed && scene.cutaway && object.use_scene_cutaway && m.draw_cap && m.opacity >= 1.0;
    any_caps = any_caps || p.caps;

    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.vertex_count()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.triangle_count()));
    if (!vertices || !indices) {
      rtcReleaseGeometry(geometry);
      throw Error("Embree: cannot allocate geometry buffers for " + source_name);
    }
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
      for (int c = 0; c < 3; ++c) vertices[3 * i + static_cast<std::size_t>(c)] = p.positions[i][c];
    for (std::size_t f = 0; f < mesh.triangle_count(); ++f)
      for (int c = 0; c < 3; ++c)
        indices[3 * f + static_cast<std::size_t>(c)] =
            static_cast<unsigned>(mesh.triangles[f][static_cast<std::size_t>(c)]);
    rtcSetGeometryUserData(geometry, &p);
    if (!p.planes.empty()) {
      rtcSetGeometryIntersectFilterFunction(geometry, &cut_filter);
      rtcSetGeometryOccludedFilterFunction(geometry, &cut_filter);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(rtc, geometry, static_cast<unsigned>(k));
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(rtc);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw Error("Embree: building the render scene failed");
}

std::vector<WorldLight> Renderer::Impl::resolve_lights(const Camera& camera) const {
  std::vector<WorldLight> out;
  const Vec3 back = -camera.forward();
  const auto to_world = [&](const Vec3& v) { return Vec3(camera.right() * v[0] + camera.up() * v[1] + back * v[2]); };
  for (const Light& l : scene.lights) {
    WorldLight w;
    w.light = l;
    if (l.camera_relative) {
      w.direction = to_world(l.direction);
      w.position = camera.target() + to_world(l.position);
      w.edge_u = to_world(l.edge_u);
      w.edge_v = to_world(l.edge_v);
    } else {
      w.direction = l.direction;
      w.position = l.position;
      w.edge_u = l.edge_u;
      w.edge_v = l.edge_v;
    }
    if (l.kind == LightKind::directional) {
      if (!(w.direction.norm() > 0) || !w.direction.allFinite()) continue;
      w.direction.normalize();
      w.cos_max = std::cos(std::clamp(l.angular_radius_deg, 0.0, 89.0) * pi / 180.0);
    }
    if (!(l.intensity > 0) || !std::isfinite(l.intensity)) continue;
    out.push_back(w);
  }
  return out;
}

Hit Renderer::Impl::intersect(const Vec3& o, const Vec3& d, double tnear, double tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(o[0]);
  rh.ray.org_y = static_cast<float>(o[1]);
  rh.ray.org_z = static_cast<float>(o[2]);
  rh.ray.dir_x = static_cast<float>(d[0]);
  rh.ray.dir_y = static_cast<float>(d[1]);
  rh.ray.dir_z = static_cast<float>(d[2]);
  rh.ray.tnear = static_cast<float>(tnear);
  rh.ray.tfar = static_cast<float>(std::min(tfar, 1e30));
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.ray.time = 0;
  rh.ray.id = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(rtc, &context, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.valid = true;
  hit.object = static_cast<int>(rh.hit.geomID);
  hit.primitive = rh.hit.primID;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  hit.t = rh.ray.tfar;
  hit.back_facing = objects[rh.hit.geomID].face_normals[rh.hit.primID].cast<double>().dot(d) > 0;
  return hit;
}

Hit Renderer::Impl::closest(const Vec3& o, const Vec3& d, double tnear) const {
  Hit first = intersect(o, d, tnear, infinity);
  if (!any_caps) return first;
  // Caps: the ray crosses the scene's cut plane from the removed side at t_plane. If that crossing point
  // lies inside a capped (closed) object, the cap is what is seen there. The point is inside an object
  // when, walking along the ray, that object's first surface is a back face.
  const CutPlane& plane = *scene.cutaway;
  const Vec3 n = plane.normal.normalized();
  const double s0 = plane.signed_distance(o + tnear * d), dn = n.dot(d);
  if (!(s0 > 0 && dn < 0)) return first;
  const double t_plane = tnear + s0 / -dn;
  if (first.valid && first.t < t_plane) return first;
  Hit current = first;
  int seen[16];
  int seen_count = 0;
  for (int step = 0; step < 16 && current.valid; ++step) {
    const PreparedObject& p = objects[static_cast<std::size_t>(current.object)];
    if (p.caps) {
      const bool was_seen = std::find(seen, seen + seen_count, current.object) != seen + seen_count;
      if (current.back_facing && !was_seen) {
        Hit cap = current;
        cap.cap = true;
        cap.t = t_plane;
        cap.back_facing = false;
        return cap;
      }
      if (!was_seen && seen_count < 16) seen[seen_count++] = current.object;
    }
    current = intersect(o, d, current.t + epsilon, infinity);
  }
  return first;
}

float Renderer::Impl::visibility(const Vec3& o, const Vec3& d, double tfar) const {
  if (!any_transparent) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = static_cast<float>(o[0]);
    ray.org_y = static_cast<float>(o[1]);
    ray.org_z = static_cast<float>(o[2]);
    ray.dir_x = static_cast<float>(d[0]);
    ray.dir_y = static_cast<float>(d[1]);
    ray.dir_z = static_cast<float>(d[2]);
    ray.tnear = 0.0f;
    ray.tfar = static_cast<float>(std::min(tfar, 1e30));
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
    ray.time = 0;
    ray.id = 0;
    rtcOccluded1(rtc, &context, &ray);
    return ray.tfar < 0 ? 0.0f : 1.0f;
  }
  // Semi-transparent surfaces let (1 - opacity) of the light through each time the ray crosses them.
  float transmission = 1.0f;
  double t = 0.0;
  for (int layer = 0; layer < 16; ++layer) {
    const Hit hit = intersect(o, d, t, tfar);
    if (!hit.valid) return transmission;
    const double opacity = objects[static_cast<std::size_t>(hit.object)].object->material.opacity;
    if (opacity >= 1.0) return 0.0f;
    transmission *= static_cast<float>(1.0 - opacity);
    if (transmission < 1e-3f) return 0.0f;
    t = hit.t + epsilon;
  }
  return transmission;
}

SurfacePoint Renderer::Impl::surface(const Hit& hit, const Vec3& o, const Vec3& d) const {
  const PreparedObject& p = objects[static_cast<std::size_t>(hit.object)];
  const SurfaceMaterial& m = p.object->material;
  SurfacePoint sp;
  sp.material = &m;
  sp.position = o + hit.t * d;
  sp.roughness = std::clamp(m.roughness, 0.02, 1.0);
  sp.f0 = 0.08 * std::clamp(m.specular, 0.0, 1.0);
  sp.skin = m.model == ShadingModel::skin;
  if (hit.cap) {
    sp.normal = sp.geometric = scene.cutaway->normal.normalized();
    sp.albedo = m.cap_colour.minCoeff() >= 0 ? m.cap_colour : Vec3f(m.base_colour * 0.45f);
    sp.roughness = 0.8;
    sp.f0 = 0.02;
    sp.skin = false;
    sp.cap = true;
    return sp;
  }
  const TriMesh& mesh = *p.mesh;
  const std::size_t f = hit.primitive;
  const Tri& tri = mesh.triangles[f];
  const float b1 = hit.u, b2 = hit.v, b0 = 1.0f - b1 - b2;
  Vec3 ng = p.face_normals[f].cast<double>();
  Vec3 n = (b0 * p.corner_normals[3 * f] + b1 * p.corner_normals[3 * f + 1] + b2 * p.corner_normals[3 * f + 2])
               .cast<double>();
  n = n.norm() > 0 ? Vec3(n.normalized()) : ng;
  Vec2 uv = Vec2::Zero();
  if (mesh.has_uvs()) {
    const Tri& tu = mesh.triangle_uvs[f];
    uv = b0 * mesh.uvs[static_cast<std::size_t>(tu[0])] + b1 * mesh.uvs[static_cast<std::size_t>(tu[1])] +
         b2 * mesh.uvs[static_cast<std::size_t>(tu[2])];
  }
  if (m.normal_map && mesh.has_uvs()) {
    const Tri& tu = mesh.triangle_uvs[f];
    const Vec3 p0 = p.positions[static_cast<std::size_t>(tri[0])].cast<double>();
    const Vec3 dp1 = p.positions[static_cast<std::size_t>(tri[1])].cast<double>() - p0;
    const Vec3 dp2 = p.positions[static_cast<std::size_t>(tri[2])].cast<double>() - p0;
    const Vec2 duv1 = mesh.uvs[static_cast<std::size_t>(tu[1])] - mesh.uvs[static_cast<std::size_t>(tu[0])];
    const Vec2 duv2 = mesh.uvs[static_cast<std::size_t>(tu[2])] - mesh.uvs[static_cast<std::size_t>(tu[0])];
    const double det = duv1[0] * duv2[1] - duv2[0] * duv1[1];
    if (std::abs(det) > 1e-20) {
      Vec3 tangent = (dp1 * duv2[1] - dp2 * duv1[1]) / det;
      const Vec3 bitangent = (dp2 * duv1[0] - dp1 * duv2[0]) / det;
      tangent -= n * n.dot(tangent);
      if (tangent.norm() > 0) {
        tangent.normalize();
        const double handedness = n.cross(tangent).dot(bitangent) < 0 ? -1.0 : 1.0;
        const Vec3 b = handedness * n.cross(tangent);
        const Vec4f t = m.normal_map->sample_uv(uv);
        const Vec3 local(2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0, 2.0 * t[2] - 1.0);
        const Vec3 perturbed = local[0] * tangent + local[1] * b + local[2] * n;
        if (perturbed.norm() > 0) n = perturbed.normalized();
      }
    }
  }
  Vec3f albedo = m.base_colour;
  switch (m.colour_source) {
    case ColourSource::constant:
      break;
    case ColourSource::vertex_colours: {
      const Vec4f c = b0 * mesh.colors[static_cast<std::size_t>(tri[0])] +
                      b1 * mesh.colors[static_cast<std::size_t>(tri[1])] +
                      b2 * mesh.colors[static_cast<std::size_t>(tri[2])];
      albedo = albedo.cwiseProduct(c.head<3>());
      break;
    }
    case ColourSource::texture:
      albedo = albedo.cwiseProduct(m.base_texture->sample_uv(uv).head<3>());
      break;
    case ColourSource::scalar_field: {
      const std::vector<double>& values = *p.field;
      const double value = b0 * values[static_cast<std::size_t>(tri[0])] +
                           b1 * values[static_cast<std::size_t>(tri[1])] +
                           b2 * values[static_cast<std::size_t>(tri[2])];
      albedo = albedo.cwiseProduct(m.colormap.map(value, m.field_min, m.field_max));
      break;
    }
  }
  if (m.wire_width_mm > 0.0) {
    // Distance of the hit to the edge opposite corner i is b_i times that corner's height, 2 A / |e_i|.
    const Vec3 q0 = p.positions[static_cast<std::size_t>(tri[0])].cast<double>();
    const Vec3 q1 = p.positions[static_cast<std::size_t>(tri[1])].cast<double>();
    const Vec3 q2 = p.positions[static_cast<std::size_t>(tri[2])].cast<double>();
    const double twice_area = (q1 - q0).cross(q2 - q0).norm();
    const double to_edge = std::min({b0 * twice_area / std::max((q2 - q1).norm(), 1e-12),
                                     b1 * twice_area / std::max((q2 - q0).norm(), 1e-12),
                                     b2 * twice_area / std::max((q1 - q0).norm(), 1e-12)});
    if (to_edge < m.wire_width_mm) albedo = m.wire_colour;
  }
  sp.albedo = albedo.cwiseMax(0.0f).cwiseMin(1.0f);
  if (hit.back_facing) {
    if (m.double_sided) {
      n = -n;
    } else {
      sp.albedo *= 0.1f;  // the inside of a single-sided surface: dark
    }
    ng = -ng;
  }
  // Interpolated normals may face away from the viewer at silhouettes: bend them back.
  const Vec3 view = -d;
  const double ndv = n.dot(view);
  if (ndv < 0.02) n = (n + (0.02 - ndv) * view).normalized();
  sp.normal = n;
  sp.geometric = ng;
  return sp;
}

Vec3f Renderer::Impl::shade(const SurfacePoint& sp, const Vec3& view, const std::vector<WorldLight>& lights,
                            const PixelSampler& sampler, int s, bool occlusion) const {
  const Vec3& n = sp.normal;
  const auto origin = [&](const Vec3& w) {
    return Vec3(sp.position + (sp.geometric.dot(w) >= 0 ? epsilon : -epsilon) * sp.geometric);
  };
  const SurfaceMaterial& m = *sp.material;
  const double sss = sp.skin ? std::clamp(m.subsurface, 0.0, 1.0) : 0.0;
  Vec3f out = Vec3f::Zero();
  const Vec3f diffuse = sp.albedo / static_cast<float>(pi);
  for (std::size_t li = 0; li < lights.size(); ++li) {
    const LightSample ls = sample_light(lights[li], sp.position, sampler.get(1 + static_cast<int>(li), s));
    if (!ls.valid) continue;
    const double ndl = n.dot(ls.wi);
    const bool shadows = lights[li].light.casts_shadows;
    // Direct part: Lambert (the share that does not scatter under the surface) and GGX specular.
    Vec3f direct = Vec3f::Zero();
    if (ndl > 0) {
      const float spec = static_cast<float>(ggx_specular(n, view, ls.wi, sp.roughness, sp.f0) * ndl);
      direct = diffuse * static_cast<float>((1.0 - sss) * ndl) + Vec3f::Constant(spec);
      const float v = shadows ? visibility(origin(ls.wi), ls.wi, ls.distance) : 1.0f;
      out += direct.cwiseProduct(ls.weight) * v;
    }
    if (sss <= 0) continue;
    // Subsurface part: wrapped lighting per channel (red wraps furthest past the terminator), giving the
    // soft, red-tinged shadow edge of skin. Its shadow ray is bent above the horizon near the terminator
    // so the object's own curvature does not cut the wrap off.
    Vec3f wrap;
    for (int c = 0; c < 3; ++c) {
      const double w = std::clamp(static_cast<double>(m.scatter_wrap[c]), 0.0, 1.0);
      wrap[c] = static_cast<float>(std::max(0.0, (ndl + w) / (1.0 + w)));
    }
    if (wrap.maxCoeff() <= 0) continue;
    float v = 1.0f;
    if (shadows) {
      Vec3 wi = ls.wi;
      if (ndl < 0.15) wi = (ls.wi - n * ndl + 0.15 * n).normalized();
      v = visibility(origin(wi), wi, ls.distance);
    }
    out += diffuse.cwiseProduct(wrap).cwiseProduct(ls.weight) * static_cast<float>(sss) * v;
  }
  // Environment light: cosine-weighted hemisphere sample, occluded by the scene (ambient occlusion).
  const Environment& env = scene.environment;
  if (occlusion) {
    const Vec3 wi = sample_cosine(n, sampler.get(0, s));
    const float v = visibility(origin(wi), wi, infinity);
    out += sp.albedo.cwiseProduct(env.radiance(wi)) * v;
  } else {
    out += sp.albedo.cwiseProduct(env.radiance(n)) * 0.8f;
  }
  // Cross-sections are lit mostly edge-on by the studio rig; a soft light from the viewer keeps their
  // colours readable.
  if (sp.cap) out += sp.albedo * static_cast<float>(0.35 * std::abs(n.dot(view)));
  return out;
}

void Renderer::Impl::trace_pixel(const Camera& camera, const RenderSettings& settings,
                                 const std::vector<WorldLight>& lights, int x, int y, Vec3f* colour,
                                 float* coverage) const {
  const int spp = settings.samples_per_pixel;
  const std::uint64_t pixel =
      static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(settings.width) + static_cast<std::uint64_t>(x);
  PixelSampler sampler(settings.seed, pixel, spp, 1 + static_cast<int>(lights.size()));
  Vec3f sum = Vec3f::Zero();
  float covered = 0.0f;
  for (int s = 0; s < spp; ++s) {
    const Vec2 jitter = sampler.pixel(s);
    const Ray3 ray = camera.ray(x + jitter[0], y + jitter[1], settings.width, settings.height);
    Vec3f accum = Vec3f::Zero();
    float transmittance = 1.0f;
    double tnear = 0.0;
    for (int layer = 0; layer < std::max(1, settings.max_layers); ++layer) {
      const Hit hit = closest(ray.origin, ray.direction, tnear);
      if (!hit.valid) break;
      const SurfaceMaterial& m = objects[static_cast<std::size_t>(hit.object)].object->material;
      if (m.opacity < 1.0 && hit.back_facing && !hit.cap) {
        tnear = hit.t + epsilon;  // overlays show only their side towards the viewer
        continue;
      }
      if (m.opacity <= 0.0) {
        tnear = hit.t + epsilon;
        continue;
      }
      const SurfacePoint sp = surface(hit, ray.origin, ray.direction);
      const Vec3f radiance = shade(sp, -ray.direction, lights, sampler, s, settings.ambient_occlusion);
      const float a = static_cast<float>(m.opacity);
      accum += transmittance * a * radiance;
      transmittance *= 1.0f - a;
      if (transmittance < 1e-3f) break;
      tnear = hit.t + epsilon;
    }
    if (settings.show_environment && transmittance > 0) {
      accum += transmittance * scene.environment.radiance(ray.direction);
      transmittance = 0;
    }
    sum += accum;
    covered += 1.0f - transmittance;
  }
  *colour = sum / static_cast<float>(spp);
  *coverage = covered / static_cast<float>(spp);
}

Image Renderer::Impl::render_raw(const Camera& camera, const RenderSettings& settings, Image* coverage_out) const {
  require_input(settings.width > 0 && settings.height > 0 && settings.width <= 16384 && settings.height <= 16384,
                "render settings", "width/height", "must be in 1..16384");
  require_input(settings.samples_per_pixel >= 1 && settings.samples_per_pixel <= 4096, "render settings",
                "samples_per_pixel", "must be in 1..4096");
  const std::vector<WorldLight> lights = resolve_lights(camera);
  Image linear(settings.width, settings.height, 3);
  Image coverage(settings.width, settings.height, 1, 0.0f, PixelEncoding::data);
  const int tile = std::clamp(settings.tile_size, 4, 256);
  const int tiles_x = (settings.width + tile - 1) / tile, tiles_y = (settings.height + tile - 1) / tile;
  parallel_for(
      0, static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y),
      [&](std::size_t index) {
        const int tx = static_cast<int>(index % static_cast<std::size_t>(tiles_x));
        const int ty = static_cast<int>(index / static_cast<std::size_t>(tiles_x));
        for (int y = ty * tile; y < std::min(settings.height, (ty + 1) * tile); ++y)
          for (int x = tx * tile; x < std::min(settings.width, (tx + 1) * tile); ++x) {
            Vec3f c;
            float a;
            trace_pixel(camera, settings, lights, x, y, &c, &a);
            float* px = linear.pixel(x, y);
            px[0] = c[0];
            px[1] = c[1];
            px[2] = c[2];
            coverage.at(x, y) = a;
          }
      },
      1);
  *coverage_out = std::move(coverage);
  return linear;
}

double Renderer::Impl::first_opaque_depth(const Camera& camera, const Ray3& ray) const {
  double tnear = 0.0;
  for (int layer = 0; layer < 16; ++layer) {
    const Hit hit = closest(ray.origin, ray.direction, tnear);
    if (!hit.valid) return infinity;
    if (objects[static_cast<std::size_t>(hit.object)].object->material.opacity >= 1.0 || hit.cap)
      return hit.t * ray.direction.dot(camera.forward());
    tnear = hit.t + epsilon;
  }
  return infinity;
}

Renderer::Renderer(const Scene& scene) : m_impl(std::make_unique<Impl>()) {
  m_impl->prepare(scene);
}

Renderer::~Renderer() = default;

Image Renderer::render_linear(const Camera& camera, const RenderSettings& settings) const {
  Image coverage;
  const Image colour = m_impl->render_raw(camera, settings, &coverage);
  Image out(settings.width, settings.height, 4);
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const float* c = colour.pixel(x, y);
      out.set_rgba(x, y, Vec4f(c[0], c[1], c[2], coverage.at(x, y)));
    }
  return out;
}

Image Renderer::depth(const Camera& camera, int width, int height) const {
  Image out(width, height, 1, 0.0f, PixelEncoding::data);
  parallel_for(
      0, static_cast<std::size_t>(height),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        for (int x = 0; x < width; ++x)
          out.at(x, y) =
              static_cast<float>(m_impl->first_opaque_depth(camera, camera.ray(x + 0.5, y + 0.5, width, height)));
      },
      1);
  return out;
}

Image Renderer::render(const Camera& camera, const RenderSettings& settings) const {
  Image coverage;
  const Image radiance = m_impl->render_raw(camera, settings, &coverage);
  Image out(settings.width, settings.height, 4, 0.0f, PixelEncoding::srgb);
  const Vec4f background = settings.background.cwiseMax(0.0f).cwiseMin(1.0f);
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const float a = coverage.at(x, y);
      const float* c = radiance.pixel(x, y);
      Vec3f shown = Vec3f::Zero();
      if (a > 0) shown = display_transform(Vec3f(c[0], c[1], c[2]) / a, settings.exposure_stops, settings.tone_map);
      const float alpha = a + background[3] * (1 - a);
      Vec3f rgb = Vec3f::Zero();
      if (alpha > 0) rgb = (shown * a + background.head<3>() * background[3] * (1 - a)) / alpha;
      out.set_rgba(x, y, Vec4f(rgb[0], rgb[1], rgb[2], alpha));
    }

  const Scene& scene = m_impl->scene;
  if (scene.lines.empty() && scene.points.empty()) return out;
  // Overlays: depth-tested against the first opaque surface through each pixel centre.
  const Image depth_buffer = depth(camera, settings.width, settings.height);
  const double tolerance = 2e-3 * m_impl->scale;
  const auto visible = [&](const Vec2& px, double z) {
    if (!(px[0] >= 0 && px[1] >= 0 && px[0] < settings.width && px[1] < settings.height)) return true;
    const int x = static_cast<int>(px[0]), y = static_cast<int>(px[1]);
    return z <= static_cast<double>(depth_buffer.at(x, y)) + tolerance;
  };
  for (const LineOverlay& line : scene.lines) {
    // Split into short pieces so the depth test follows the line; hidden pieces are drawn faintly.
    Vec2 a, b;
    double za, zb;
    if (!camera.project(line.from, settings.width, settings.height, &a, &za) ||
        !camera.project(line.to, settings.width, settings.height, &b, &zb))
      continue;
    const double length_px = (b - a).norm();
    const int pieces = std::isfinite(length_px) ? static_cast<int>(std::clamp(length_px / 2.0, 1.0, 4096.0)) : 1;
    for (int k = 0; k < pieces; ++k) {
      const double t0 = static_cast<double>(k) / pieces, t1 = static_cast<double>(k + 1) / pieces;
      const Vec3 p0 = line.from + t0 * (line.to - line.from), p1 = line.from + t1 * (line.to - line.from);
      Vec2 q0, q1;
      double z0, z1;
      if (!camera.project(p0, settings.width, settings.height, &q0, &z0) ||
          !camera.project(p1, settings.width, settings.height, &q1, &z1))
        continue;
      const Vec3 mid = 0.5 * (p0 + p1);
      Vec2 qm;
      double zm;
      camera.project(mid, settings.width, settings.height, &qm, &zm);
      Vec4f colour = line.colour;
      if (line.depth_test && !visible(qm, zm)) colour[3] *= 0.2f;
      draw_line(out, q0, q1, colour, line.width_px);
    }
  }
  for (const PointOverlay& point : scene.points) {
    Vec2 q;
    double z;
    if (!camera.project(point.position, settings.width, settings.height, &q, &z)) continue;
    Vec4f colour = point.colour;
    if (point.depth_test && !visible(q, z)) colour[3] *= 0.25f;
    draw_disc(out, q, point.radius_px, colour, std::max(1.0, 0.3 * point.radius_px),
              Vec4f(1.0f, 1.0f, 1.0f, colour[3]));
    if (!point.label.empty()) {
      const double size = std::max(10.0, 3.0 * point.radius_px);
      draw_text_with_halo(out, q[0] + point.radius_px + 4, q[1] - 0.6 * size, point.label, size,
                          Vec4f(0.05f, 0.05f, 0.05f, colour[3]), Vec4f(1.0f, 1.0f, 1.0f, 0.8f * colour[3]));
    }
  }
  return out;
}

Image Renderer::render(const RenderSettings& settings) const {
  return render(m_impl->scene.camera, settings);
}

Image render(const Scene& scene, const RenderSettings& settings) {
  return Renderer(scene).render(settings);
}

}  // namespace forensim
