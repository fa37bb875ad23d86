#include "wound/wound_job.hpp"

#include <cmath>
#include <optional>

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"
#include "wound/bruise.hpp"
#include "wound/duration.hpp"
#include "wound/screen_stroke.hpp"

namespace forensim {

std::optional<Vec3> surface_point_at_uv(const TriMesh& mesh, const Vec2& uv) {
  for (std::size_t f = 0; f < mesh.triangle_uvs.size(); ++f) {
    const auto& tu = mesh.triangle_uvs[f];
    const Vec2 a = mesh.uvs[tu[0]], b = mesh.uvs[tu[1]], c = mesh.uvs[tu[2]];
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(det) < 1e-18) continue;
    const double l1 = ((uv.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (uv.y() - a.y())) / det;
    const double l2 = ((b.x() - a.x()) * (uv.y() - a.y()) - (uv.x() - a.x()) * (b.y() - a.y())) / det;
    const double l0 = 1.0 - l1 - l2;
    const double eps = -1e-9;
    if (l0 < eps || l1 < eps || l2 < eps) continue;
    const auto& t = mesh.triangles[f];
    return l0 * mesh.positions[t[0]] + l1 * mesh.positions[t[1]] + l2 * mesh.positions[t[2]];
  }
  return std::nullopt;
}

namespace {

Vec3 read_vec3(const JobNode& node, const std::string& key) {
  const auto v = node.require<std::vector<double>>(key);
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
    node.fail(key, "expected three finite numbers");
  }
  return Vec3(v[0], v[1], v[2]);
}

// The camera of a screen stroke: a named view framed on the mesh ({"view", "axes"}) or an explicit one
// ({"eye", "target", "up", "fov_deg"}), and the image size its pixels refer to.
StrokeScreen read_stroke_screen(const JobNode& node, const TriMesh& mesh) {
  StrokeScreen screen;
  screen.width = static_cast<int>(node.get_integer("width", 1024, 1, 16384));
  screen.height = static_cast<int>(node.get_integer("height", 1024, 1, 16384));
  const double fov = node.get_number("fov_deg", 30.0, 1.0, 170.0);
  if (node.has("eye")) {
    try {
      screen.camera = Camera::look_at(read_vec3(node, "eye"), read_vec3(node, "target"), read_vec3(node, "up"), fov);
    } catch (const InputError& err) {
      node.fail("eye", err.problem());
    }
    return screen;
  }
  const std::string view = node.get_choice("view", "front", view_names());
  FramingOptions framing;
  framing.vertical_fov_deg = fov;
  // "lps": CT and phantom meshes (+Z up, -Y front); "y_up": glTF and most scans (+Y up, +Z front).
  if (node.get_choice("axes", "lps", {"lps", "y_up"}) == "y_up") framing.axes = {Vec3::UnitY(), Vec3::UnitZ()};
  screen.camera = frame_view(bounding_box(mesh.positions), view_from_name(view),
                             static_cast<double>(screen.width) / static_cast<double>(screen.height), framing);
  return screen;
}

}  // namespace

WoundJob read_wound_job(const JobNode& root, const TriMesh& mesh, const std::optional<std::string>& type_override) {
  WoundJob job;
  root.get_integer("version", 1, 1, 1);
  const std::string job_type = root.get_choice("type", "abrasion", {"abrasion", "bruise"});
  job.type = type_override.value_or(job_type);
  if (job.type != "abrasion" && job.type != "bruise") root.fail("type", "unknown wound type '" + job.type + "'");
  job.canvas.shape = root.get_choice("shape", "strokes", {"strokes", "convex_hull"}) == "strokes"
                         ? ShapeMode::strokes
                         : ShapeMode::convex_hull;
  job.canvas.distance =
      root.get_choice("distance", "surface", {"surface", "uv"}) == "surface" ? DistanceMode::surface : DistanceMode::uv;

  const JobNode ab = root.child("abrasion");
  job.abrasion.thesis_texels_per_mm = ab.get_number("thesis_texels_per_mm", 8.0, 0.1, 1000.0);
  job.abrasion.glow_thickness_px = ab.get_number("glow_thickness_px", 100.0, 1.0, 10000.0);
  job.abrasion.scab_gradient_px = ab.get_number("scab_gradient_px", 100.0, 1.0, 10000.0);
  job.abrasion.scab_height_mm = ab.get_number("scab_height_mm", 0.8, 0.0, 20.0);
  job.abrasion.skin_reflection = static_cast<float>(ab.get_number("skin_reflection", 0.25, 0.0, 1.0));
  job.abrasion.thesis_closing_distance = ab.get<bool>("thesis_closing_distance", false);

  const auto strokes = root.children("strokes");
  std::optional<RayCaster> caster;  // built on the first screen stroke, shared by the others
  if (strokes.empty()) root.fail("strokes", "at least one stroke is needed");
  for (std::size_t s = 0; s < strokes.size(); ++s) {
    const JobNode& node = strokes[s];
    WoundStroke stroke;
    stroke.radius_mm = node.get_number("radius_mm", 3.0, 0.05, 500.0);
    const bool has_points = node.has("points"), has_uv = node.has("uv"), has_screen = node.has("screen");
    if (int(has_points) + int(has_uv) + int(has_screen) != 1) {
      node.fail("points", "give one of \"points\" (mm), \"uv\" or \"screen\" (pixels with a \"camera\")");
    }
    if (has_screen) {
      const StrokeScreen screen = read_stroke_screen(node.child("camera"), mesh);
      const auto pixels = node.require<std::vector<std::vector<double>>>("screen");
      if (pixels.empty() || pixels.size() > 100000) node.fail("screen", "needs 1 to 100000 points");
      std::vector<Vec2> points;
      for (std::size_t i = 0; i < pixels.size(); ++i) {
        const auto& p = pixels[i];
        if (p.size() != 2 || !std::isfinite(p[0]) || !std::isfinite(p[1])) {
          node.fail("screen", "point " + std::to_string(i) + " is not two finite numbers");
        }
        points.push_back(Vec2(p[0], p[1]));
      }
      try {
        if (!caster) caster.emplace(mesh);
        stroke = record_screen_stroke(mesh, *caster, screen, points, stroke.radius_mm).stroke;
      } catch (const InputError& err) {
        node.fail("screen", err.problem());
      }
    } else if (has_points) {
      const auto points = node.require<std::vector<std::vector<double>>>("points");
      if (points.empty() || points.size() > 100000) node.fail("points", "needs 1 to 100000 points");
      for (std::size_t i = 0; i < points.size(); ++i) {
        const auto& p = points[i];
        if (p.size() != 3 || !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
          node.fail("points", "point " + std::to_string(i) + " is not three finite numbers");
        }
        stroke.points.push_back(Vec3(p[0], p[1], p[2]));
      }
    } else {
      const auto uvs = node.require<std::vector<std::vector<double>>>("uv");
      if (uvs.empty() || uvs.size() > 100000) node.fail("uv", "needs 1 to 100000 points");
      for (std::size_t i = 0; i < uvs.size(); ++i) {
        const auto& p = uvs[i];
        if (p.size() != 2 || !std::isfinite(p[0]) || !std::isfinite(p[1])) {
          node.fail("uv", "point " + std::to_string(i) + " is not two finite numbers");
        }
        const auto q = surface_point_at_uv(mesh, Vec2(p[0], p[1]));
        if (!q) node.fail("uv", "point " + std::to_string(i) + " lies in no UV triangle of the mesh (off the mesh)");
        stroke.points.push_back(*q);
      }
    }
    job.strokes.push_back(std::move(stroke));
  }

  const auto keys = root.children("keys");
  if (keys.empty()) {
    job.timeline = job.type == "abrasion" ? default_abrasion_timeline(job.abrasion) : default_bruise_timeline();
  } else {
    std::vector<std::pair<std::string, std::shared_ptr<const KeyPosition>>> made;
    const std::vector<std::string> phases =
        job.type == "abrasion"
            ? std::vector<std::string>{"vasoconstriction", "vasodilation", "scab_forming", "scab", "maturation"}
            : std::vector<std::string>{"fresh", "blue", "green", "yellow", "faded"};
    for (const JobNode& k : keys) {
      TimelineEntry e;
      const std::string phase = k.get_choice("phase", phases.front(), phases);
      std::shared_ptr<const KeyPosition> key;
      for (const auto& [n, kp] : made) {
        if (n == phase) key = kp;
      }
      if (!key) {
        key = job.type == "abrasion"
                  ? make_abrasion_key(phase, job.abrasion)
                  : std::shared_ptr<const KeyPosition>(std::make_shared<BruiseKey>(bruise_stage(phase)));
        made.push_back({phase, key});
      }
      e.key = key;
      const std::string time = k.require<std::string>("time");
      try {
        e.time_s = parse_duration(time, "time");
      } catch (const InputError& err) {
        k.fail("time", err.problem());
      }
      e.local_position = k.get_number("position", 0.0, 0.0, 1.0);
      e.label = k.get<std::string>("label", phase);
      job.timeline.push_back(std::move(e));
    }
  }
  return job;
}

}  // namespace forensim
