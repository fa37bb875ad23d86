#include "craniofacial/interpolated_landmarks.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/ray_caster.hpp"

namespace forensim {
namespace {

constexpr double degrees = std::numbers::pi / 180.0;

struct Hit {
  Vec3 point, normal;
};

/// Normal facing the ray's origin.
Vec3 facing(const Vec3& normal, const Vec3& direction) {
  return normal.dot(direction) > 0.0 ? Vec3(-normal) : normal;
}

/// First hit of the ray from outside `origin` along unit `direction`, with the skull's vertex normals
/// interpolated there: each is the area-weighted mean of the face normals around a vertex, so the direction is
/// a patch average over the vertex's ring and turns with the skull.
std::optional<Hit> first_hit(const TriMesh& skull, const std::vector<Vec3>& vertex_normals, const RayCaster& rays,
                             const Vec3& origin, const Vec3& direction, double t_max) {
  const auto hit = rays.intersect(origin, direction, 0.0, t_max);
  if (!hit) return std::nullopt;
  const Tri& t = skull.triangles[static_cast<std::size_t>(hit->triangle)];
  Vec3 normal = hit->barycentric(0) * vertex_normals[static_cast<std::size_t>(t[0])] +
                hit->barycentric(1) * vertex_normals[static_cast<std::size_t>(t[1])] +
                hit->barycentric(2) * vertex_normals[static_cast<std::size_t>(t[2])];
  if (normal.norm() == 0.0) normal = hit->normal;
  return Hit{hit->point, facing(normal.normalized(), direction)};
}

}  // namespace

std::vector<LandmarkArc> default_mandible_arcs() {
  std::vector<LandmarkArc> arcs;
  for (const char* side : {"_L", "_R"}) {
    const std::string s(side);
    arcs.push_back({"mmb" + s, "go" + s, 2});
    arcs.push_back({"go" + s, "mr" + s, 1});
  }
  return arcs;
}

std::vector<Vec3> InterpolatedLandmarks::skin_targets() const {
  std::vector<Vec3> out(skull.size());
  for (std::size_t i = 0; i < skull.size(); ++i) out[i] = skull[i] + depth_mm[i] * normals[i];
  return out;
}

InterpolatedLandmarks interpolate_landmarks(const TriMesh& skull, const RayCaster& skull_rays,
                                            const LandmarkDepths& landmarks,
                                            const LandmarkInterpolationOptions& options) {
  const char* const source = "landmark interpolation";
  require_input(
      landmarks.skull.size() == landmarks.names.size() && landmarks.depth_vectors.size() == landmarks.names.size(),
      source, "landmarks", "names, skull positions and depth vectors differ in number");
  require_input(options.cranium_rings >= 1 && options.cranium_rings <= 64, source, "cranium_rings",
                "must be in [1, 64]");
  require_input(options.cranium_sectors >= 1 && options.cranium_sectors <= 64, source, "cranium_sectors",
                "must be in [1, 64]");
  require_input(options.cranium_min_elevation_front_deg >= 0.0 && options.cranium_min_elevation_front_deg <= 89.0 &&
                    options.cranium_min_elevation_side_deg >= 0.0 && options.cranium_min_elevation_side_deg <= 89.0,
                source, "cranium_min_elevation", "must be in [0, 89] degrees");
  require_input(skull_rays.triangle_count() == skull.triangles.size(), source, "skull",
                "the ray caster was not built from this skull mesh");
  std::vector<Vec3> vertex_normals = skull.normals;
  if (vertex_normals.size() != skull.positions.size()) {
    TriMesh copy;
    copy.positions = skull.positions;
    copy.triangles = skull.triangles;
    compute_normals(copy);
    vertex_normals = std::move(copy.normals);
  }
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < landmarks.names.size(); ++i) {
    require_input(std::isfinite(landmarks.skull[i].sum()) && std::isfinite(landmarks.depth_vectors[i].sum()), source,
                  "landmark " + landmarks.names[i], "non-finite position or depth vector");
    index.emplace(landmarks.names[i], i);
  }
  InterpolatedLandmarks out;
  auto add = [&](const std::string& name, const Hit& h, double depth) {
    out.names.push_back(name);
    out.skull.push_back(h.point);
    out.normals.push_back(h.normal);
    out.depth_mm.push_back(depth);
  };

  if (options.cranium && index.count("g") && index.count("v") && index.count("op")) {
    const Vec3 g = landmarks.skull[index["g"]], v = landmarks.skull[index["v"]], op = landmarks.skull[index["op"]];
    const Vec3 origin = 0.5 * (g + op);
    const Vec3 forward = (g - op).normalized();
    Vec3 up = (v - origin) - (v - origin).dot(forward) * forward;
    const double height = up.norm();
    up /= height;
    const Vec3 lateral = up.cross(forward);
    const double half_length = 0.5 * (g - op).norm();
    double half_breadth = 0.75 * half_length;
    if (index.count("zy_L") && index.count("zy_R")) {
      half_breadth = 0.5 * std::abs((landmarks.skull[index["zy_L"]] - landmarks.skull[index["zy_R"]]).dot(lateral));
    }
    require_input(height > 0.0 && half_length > 0.0 && half_breadth > 0.0, source, "landmarks g, v, op",
                  "do not span a head frame");
    // Frame coordinates normalised by the head's half-length, height and half-breadth: directions in them point
    // to corresponding places on skulls of different proportions.
    auto normalised = [&](const Vec3& p) {
      const Vec3 d = p - origin;
      return Vec3(d.dot(forward) / half_length, d.dot(lateral) / half_breadth, d.dot(up) / height);
    };
    const char* cranial[] = {"g", "v", "op"};
    auto depth_at = [&](const Vec3& p) {
      const Vec3 x = normalised(p);
      double sum_w = 0.0, sum = 0.0;
      for (const char* name : cranial) {
        const std::size_t i = index[name];
        const double d2 = (normalised(landmarks.skull[i]) - x).squaredNorm();
        const double depth = landmarks.depth_vectors[i].norm();
        if (d2 < 1e-12) return depth;
        sum_w += 1.0 / d2;
        sum += depth / d2;
      }
      return sum / sum_w;
    };
    auto sample = [&](double azimuth, double elevation) -> std::optional<Hit> {
      const Vec3 e = std::cos(elevation) * std::cos(azimuth) * half_length * forward +
                     std::cos(elevation) * std::sin(azimuth) * half_breadth * lateral +
                     std::sin(elevation) * height * up;
      const Vec3 dir = -e.normalized();
      return first_hit(skull, vertex_normals, skull_rays, origin + 2.0 * e, dir, 2.0 * e.norm());
    };
    for (int r = 0; r < options.cranium_rings; ++r) {
      for (int s = 0; s < options.cranium_sectors; ++s) {
        const double azimuth = 2.0 * std::numbers::pi * s / options.cranium_sectors;
        const double lowest = (options.cranium_min_elevation_front_deg +
                               (options.cranium_min_elevation_side_deg - options.cranium_min_elevation_front_deg) *
                                   std::abs(std::sin(azimuth))) *
                              degrees;
        const double elevation = lowest + (0.5 * std::numbers::pi - lowest) * r / options.cranium_rings;
        if (const auto h = sample(azimuth, elevation)) {
          add("cranium_r" + std::to_string(r) + "_s" + std::to_string(s), *h, depth_at(h->point));
        }
      }
    }
    if (const auto h = sample(0.0, 0.5 * std::numbers::pi)) add("cranium_top", *h, depth_at(h->point));
  }

  if (options.mandible) {
    const ClosestPointQuery surface(skull);
    auto normal_at = [&](const ClosestPoint& c) {
      const Tri& f = skull.triangles[static_cast<std::size_t>(c.triangle)];
      const Vec3 n = c.barycentric(0) * vertex_normals[static_cast<std::size_t>(f[0])] +
                     c.barycentric(1) * vertex_normals[static_cast<std::size_t>(f[1])] +
                     c.barycentric(2) * vertex_normals[static_cast<std::size_t>(f[2])];
      return n.normalized();
    };
    for (const LandmarkArc& arc : options.mandible_arcs) {
      require_input(arc.count >= 1 && arc.count <= 32, source, "arc " + arc.from + "~" + arc.to,
                    "count must be in [1, 32]");
      if (!index.count(arc.from) || !index.count(arc.to)) continue;
      const std::size_t a = index[arc.from], b = index[arc.to];
      const double da = landmarks.depth_vectors[a].norm(), db = landmarks.depth_vectors[b].norm();
      require_input(da > 0.0 && db > 0.0, source, "arc " + arc.from + "~" + arc.to, "zero depth vector at an end");
      // Walk over the outer bone from one landmark toward the other: steps of 1/64 of their distance along the
      // surface's tangent plane, each put back onto the surface by its closest point. A straight chord would
      // cut through the jaw's arch and land on its inner side.
      const Vec3 end = landmarks.skull[b];
      const double step = (end - landmarks.skull[a]).norm() / 64.0;
      if (step <= 0.0) continue;
      std::vector<ClosestPoint> path{*surface.query(landmarks.skull[a])};
      std::vector<double> arclength{0.0};
      for (int k = 0; k < 256 && (path.back().point - end).norm() > step; ++k) {
        const Vec3 n = normal_at(path.back());
        Vec3 d = end - path.back().point;
        d -= d.dot(n) * n;
        if (d.norm() < 1e-12) break;
        const ClosestPoint next = *surface.query(path.back().point + step * d.normalized());
        arclength.push_back(arclength.back() + (next.point - path.back().point).norm());
        path.push_back(next);
      }
      path.push_back(*surface.query(end));
      arclength.push_back(arclength.back() + (path.back().point - path[path.size() - 2].point).norm());
      for (int k = 1; k <= arc.count; ++k) {
        const double t = static_cast<double>(k) / (arc.count + 1);
        const double want = t * arclength.back();
        std::size_t j = 0;
        while (j + 1 < arclength.size() && arclength[j + 1] < want) ++j;
        const ClosestPoint& c = path[j];
        add(arc.from + "~" + arc.to + "_" + std::to_string(k), Hit{c.point, normal_at(c)}, (1.0 - t) * da + t * db);
      }
    }
  }
  return out;
}

std::vector<Vec3> skin_points_along_normals(const RayCaster& skin_rays, const InterpolatedLandmarks& points) {
  std::vector<Vec3> out(points.skull.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto h = skin_rays.intersect(points.skull[i], points.normals[i], 0.0, 100.0);
    out[i] = h ? h->point : points.skull[i] + points.depth_mm[i] * points.normals[i];
  }
  return out;
}

}  // namespace forensim
