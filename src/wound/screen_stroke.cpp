#include "wound/screen_stroke.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace forensim {

Vec3 barycentric_from_areas(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  const Vec3 u = b - a, v = c - a, w = p - a;
  const double area = u.cross(v).norm();
  if (!(area > 0.0)) return Vec3(1.0, 0.0, 0.0);
  const double r = v.cross(w).norm() / area;
  const double t = u.cross(w).norm() / area;
  return Vec3(1.0 - r - t, r, t);
}

RecordedStroke record_screen_stroke(const TriMesh& mesh, const StrokeScreen& screen,
                                    const std::vector<Vec2>& screen_points, double radius_mm) {
  return record_screen_stroke(mesh, RayCaster(mesh), screen, screen_points, radius_mm);
}

RecordedStroke record_screen_stroke(const TriMesh& mesh, const RayCaster& caster, const StrokeScreen& screen,
                                    const std::vector<Vec2>& screen_points, double radius_mm) {
  const std::string source = "wound stroke";
  if (mesh.triangle_uvs.size() != mesh.triangles.size() || mesh.uvs.empty()) {
    throw InputError(source, "mesh", "the mesh has no UV coordinates to record");
  }
  if (screen.width <= 0 || screen.height <= 0) {
    throw InputError(source, "screen", "the screen size must be positive");
  }
  if (!(radius_mm > 0.0) || !std::isfinite(radius_mm)) {
    throw InputError(source, "radius_mm", "the brush radius must be a positive number");
  }
  RecordedStroke out;
  out.stroke.radius_mm = radius_mm;
  if (screen_points.empty()) throw InputError(source, "screen", "the stroke has no points");
  for (std::size_t i = 0; i < screen_points.size(); ++i) {
    const Vec2& s = screen_points[i];
    if (!std::isfinite(s.x()) || !std::isfinite(s.y())) {
      throw InputError(source, "screen point " + std::to_string(i), "is not two finite numbers");
    }
    // Chapter 4.2.1: the ray from the camera through the pointer's viewport position.
    const Ray3 ray = screen.camera.ray(s.x(), s.y(), screen.width, screen.height);
    const auto hit = caster.intersect(ray.origin, ray.direction);
    if (!hit) {
      ++out.missed;
      continue;
    }
    const auto& tri = mesh.triangles[static_cast<std::size_t>(hit->triangle)];
    const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
    RecordedPoint rp;
    rp.screen_index = i;
    rp.triangle = hit->triangle;
    rp.barycentric = barycentric_from_areas(a, b, c, hit->point);  // eq. 4.2
    rp.position = barycentric_blend(rp.barycentric, a, b, c);      // eq. 4.1
    const auto& tu = mesh.triangle_uvs[static_cast<std::size_t>(hit->triangle)];
    rp.uv = barycentric_blend(rp.barycentric, mesh.uvs[tu[0]], mesh.uvs[tu[1]], mesh.uvs[tu[2]]);  // eq. 4.3
    out.stroke.points.push_back(rp.position);
    out.points.push_back(rp);
  }
  if (out.points.empty()) {
    throw InputError(
        source, "screen",
        "none of the " + std::to_string(screen_points.size()) + " screen points hits the mesh from this camera");
  }
  return out;
}

}  // namespace forensim
