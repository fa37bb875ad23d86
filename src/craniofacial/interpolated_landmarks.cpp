#include "craniofacial/interpolated_landmarks.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include "core/error.hpp"
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

/// First hit of the ray from outside `origin` along unit `direction`, with the normal averaged over the hits of
/// four more rays `patch` mm to the sides.
std::optional<Hit> hit_with_patch(const RayCaster& rays, const Vec3& origin, const Vec3& direction, double t_max,
                                  double patch) {
  const auto centre = rays.intersect(origin, direction, 0.0, t_max);
  if (!centre) return std::nullopt;
  Vec3 normal = facing(centre->normal, direction);
  if (patch > 0.0) {
    const Vec3 t1 = direction.unitOrthogonal();
    const Vec3 t2 = direction.cross(t1);
    const Vec3 offsets[4] = {t1, -t1, t2, -t2};
    for (const Vec3& o : offsets) {
      const auto h = rays.intersect(origin + patch * o, direction, 0.0, t_max);
      // Only hits on the same sheet of bone count (not a far wall seen past an edge).
      if (h && std::abs(h->t - centre->t) < 3.0 * patch) normal += facing(h->normal, direction);
    }
  }
  return Hit{centre->point, normal.normalized()};
}

}  // namespace

std::vector<LandmarkArc> default_mandible_arcs() {
  std::vector<LandmarkArc> arcs;
  for (const char* side : {"_L", "_R"}) {
    const std::string s(side);
    arcs.push_back({"me", "mmb" + s, 2});
    arcs.push_back({"mmb" + s, "go" + s, 2});
    arcs.push_back({"go" + s, "mr" + s, 1});
    arcs.push_back({"pg", "mmb" + s, 2});
  }
  return arcs;
}

std::vector<Vec3> InterpolatedLandmarks::skin_targets() const {
  std::vector<Vec3> out(skull.size());
  for (std::size_t i = 0; i < skull.size(); ++i) out[i] = skull[i] + depth_mm[i] * normals[i];
  return out;
}

InterpolatedLandmarks interpolate_landmarks(const RayCaster& skull_rays, const LandmarkDepths& landmarks,
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
  require_input(options.normal_patch_mm >= 0.0 && options.normal_patch_mm <= 20.0, source, "normal_patch_mm",
                "must be in [0, 20]");
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
      return hit_with_patch(skull_rays, origin + 2.0 * e, dir, 2.0 * e.norm(), options.normal_patch_mm);
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
    for (const LandmarkArc& arc : options.mandible_arcs) {
      require_input(arc.count >= 1 && arc.count <= 32, source, "arc " + arc.from + "~" + arc.to,
                    "count must be in [1, 32]");
      if (!index.count(arc.from) || !index.count(arc.to)) continue;
      const std::size_t a = index[arc.from], b = index[arc.to];
      const double da = landmarks.depth_vectors[a].norm(), db = landmarks.depth_vectors[b].norm();
      require_input(da > 0.0 && db > 0.0, source, "arc " + arc.from + "~" + arc.to, "zero depth vector at an end");
      for (int k = 1; k <= arc.count; ++k) {
        const double t = static_cast<double>(k) / (arc.count + 1);
        const Vec3 chord = (1.0 - t) * landmarks.skull[a] + t * landmarks.skull[b];
        const Vec3 n = ((1.0 - t) * landmarks.depth_vectors[a] / da + t * landmarks.depth_vectors[b] / db).normalized();
        if (const auto h = hit_with_patch(skull_rays, chord + 30.0 * n, -n, 60.0, options.normal_patch_mm)) {
          add(arc.from + "~" + arc.to + "_" + std::to_string(k), *h, (1.0 - t) * da + t * db);
        }
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
