#pragma once
/// Lights for result pictures: directional lights with an angular radius (the sun or a distant softbox:
/// soft shadow edges), spherical and rectangular area lights, and a sky/ground gradient environment.

#include <vector>

#include "core/types.hpp"

namespace forensim {

enum class LightKind { directional, sphere, rectangle };

struct Light {
  LightKind kind = LightKind::directional;
  /// Directional: unit-free direction from the scene towards the light.
  Vec3 direction = Vec3(0, 0, 1);
  /// Directional: angular radius in degrees of the light's disc as seen from the scene (0 = hard shadows).
  double angular_radius_deg = 3.0;
  /// Sphere: centre; rectangle: one corner (scene units, mm).
  Vec3 position = Vec3::Zero();
  /// Sphere radius (mm).
  double radius = 10.0;
  /// Rectangle: the two edges from `position`; it emits on the side of edge_u x edge_v.
  Vec3 edge_u = Vec3(100, 0, 0);
  Vec3 edge_v = Vec3(0, 100, 0);
  /// Linear RGB colour, multiplied by `intensity`. Directional: irradiance on a surface facing the light
  /// (1 = a white Lambertian surface shows its albedo). Sphere and rectangle: emitted radiance.
  Vec3f colour = Vec3f(1, 1, 1);
  double intensity = 1.0;
  /// When true, direction/position/edges are given in the camera frame (x right, y up, z from the
  /// target towards the camera) so the rig turns with the camera in turntables.
  bool camera_relative = false;
  bool casts_shadows = true;

  /// Directional light from `direction` (towards the light) with the given colour, intensity and softness.
  static Light directional(const Vec3& direction, double intensity = 1.0, double angular_radius_deg = 3.0,
                           const Vec3f& colour = Vec3f(1, 1, 1));
  /// Spherical area light.
  static Light sphere(const Vec3& centre, double radius, double intensity, const Vec3f& colour = Vec3f(1, 1, 1));
  /// Rectangular area light with corner `corner` and edges `u`, `v`, emitting towards u x v.
  static Light rectangle(const Vec3& corner, const Vec3& u, const Vec3& v, double intensity,
                         const Vec3f& colour = Vec3f(1, 1, 1));
};

/// Light from the surroundings: a vertical gradient from `ground` (below the horizon) to `sky` (zenith)
/// around `up`, seen by ambient-occlusion rays; also the colour behind the subject when
/// RenderSettings::show_environment is set.
struct Environment {
  Vec3f sky = Vec3f(0.24f, 0.26f, 0.30f);
  Vec3f horizon = Vec3f(0.17f, 0.17f, 0.17f);
  Vec3f ground = Vec3f(0.07f, 0.065f, 0.06f);
  Vec3 up = Vec3::UnitZ();
  double intensity = 1.0;

  /// Linear radiance arriving from unit direction `d`.
  Vec3f radiance(const Vec3& d) const;
};

/// Three-point studio rig in the camera frame: a warm key light above-left in front, a cool, weaker fill
/// from the right, and a rim light from behind; all soft (a few degrees).
std::vector<Light> studio_lights();

}  // namespace forensim
