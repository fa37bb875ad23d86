#include "render/light.hpp"

#include <algorithm>
#include <cmath>

namespace forensim {

Light Light::directional(const Vec3& direction, double intensity, double angular_radius_deg, const Vec3f& colour) {
  Light l;
  l.kind = LightKind::directional;
  l.direction = direction;
  l.intensity = intensity;
  l.angular_radius_deg = angular_radius_deg;
  l.colour = colour;
  return l;
}

Light Light::sphere(const Vec3& centre, double radius, double intensity, const Vec3f& colour) {
  Light l;
  l.kind = LightKind::sphere;
  l.position = centre;
  l.radius = radius;
  l.intensity = intensity;
  l.colour = colour;
  return l;
}

Light Light::rectangle(const Vec3& corner, const Vec3& u, const Vec3& v, double intensity, const Vec3f& colour) {
  Light l;
  l.kind = LightKind::rectangle;
  l.position = corner;
  l.edge_u = u;
  l.edge_v = v;
  l.intensity = intensity;
  l.colour = colour;
  return l;
}

Vec3f Environment::radiance(const Vec3& d) const {
  const double n = up.norm();
  const double h = n > 0 ? std::clamp(d.dot(up) / n, -1.0, 1.0) : 0.0;
  Vec3f c;
  if (h >= 0) {
    const float t = static_cast<float>(std::sqrt(h));
    c = horizon * (1 - t) + sky * t;
  } else {
    const float t = static_cast<float>(std::min(1.0, -h * 4.0));
    c = horizon * (1 - t) + ground * t;
  }
  return c * static_cast<float>(intensity);
}

std::vector<Light> studio_lights() {
  std::vector<Light> rig;
  Light key = Light::directional(Vec3(-0.55, 0.55, 0.65), 0.95, 4.0, Vec3f(1.0f, 0.96f, 0.90f));
  key.camera_relative = true;
  Light fill = Light::directional(Vec3(0.75, 0.05, 0.6), 0.3, 8.0, Vec3f(0.88f, 0.93f, 1.0f));
  fill.camera_relative = true;
  fill.casts_shadows = false;
  Light rim = Light::directional(Vec3(0.3, 0.6, -0.75), 0.8, 3.0, Vec3f(1.0f, 1.0f, 1.0f));
  rim.camera_relative = true;
  rig.push_back(key);
  rig.push_back(fill);
  rig.push_back(rim);
  return rig;
}

}  // namespace forensim
