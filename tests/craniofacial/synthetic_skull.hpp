#pragma once
// A skull-like test surface with known landmarks, and a known similarity plus smooth deformation of it, for the
// registration and detection tests. Head coordinates LPS (x left, y posterior, z superior), mm.

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "craniofacial/head_frame.hpp"
#include "craniofacial/landmark_set.hpp"
#include "craniofacial/skull_registration.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim::test {

struct Bump {
  Vec3 direction;  // unit, from the centre
  double amplitude_mm;
  double width_rad;
};

inline const std::vector<Bump>& skull_bumps() {
  static const std::vector<Bump> bumps = {
      {Vec3(0, -0.92, -0.4).normalized(), 16.0, 0.18},     // chin
      {Vec3(0, -1, 0.15).normalized(), 6.0, 0.15},         // brow
      {Vec3(0.93, -0.3, -0.2).normalized(), 10.0, 0.15},   // left zygomatic arch
      {Vec3(-0.93, -0.3, -0.2).normalized(), 10.0, 0.15},  // right zygomatic arch
      {Vec3(0, 0.95, 0.3).normalized(), 6.0, 0.3},         // occiput
  };
  return bumps;
}

/// The surface point in unit direction u: an ellipsoid (70, 90, 80) mm with radial bumps.
inline Vec3 skull_point(const Vec3& u) {
  Vec3 p(70.0 * u.x(), 90.0 * u.y(), 80.0 * u.z());
  const Vec3 radial = p.normalized();
  for (const Bump& b : skull_bumps()) {
    const double angle = std::acos(std::clamp(u.dot(b.direction), -1.0, 1.0));
    p += b.amplitude_mm * std::exp(-angle * angle / (2.0 * b.width_rad * b.width_rad)) * radial;
  }
  return p;
}

inline TriMesh skull_mesh(int subdivisions = 6) {
  TriMesh mesh = make_icosphere(Vec3::Zero(), 1.0, subdivisions);
  for (Vec3& p : mesh.positions) p = skull_point(p.normalized());
  mesh.normals.clear();
  return mesh;
}

/// Rough landmark guesses (before refinement by definition) and Frankfort points.
inline LandmarkSet rough_skull_landmarks() {
  LandmarkSet set("synthetic skull");
  const auto add = [&](const std::string& name, const Vec3& dir) {
    set.add({name, skull_point(dir.normalized()), LandmarkSource::imported, 1.0});
  };
  add("v", Vec3(0.02, 0.03, 1));
  add("op", Vec3(0, 0.95, 0.28));
  add("g", Vec3(0, -1, 0.17));
  add("pg", Vec3(0, -0.92, -0.37));
  add("zy_L", Vec3(0.93, -0.28, -0.2));
  add("zy_R", Vec3(-0.93, -0.28, -0.2));
  add("sg", Vec3(0, -0.9, 0.45));
  add("po_L", Vec3(1, 0.15, 0.05));
  add("po_R", Vec3(-1, 0.15, 0.05));
  add("or_L", Vec3(0.45, -0.85, 0.05));
  add("or_R", Vec3(-0.45, -0.85, 0.05));
  return set;
}

/// The synthetic skull's own head frame: identity axes, x = 0 the midsagittal plane, z = 0 the Frankfort plane.
inline HeadFrame identity_frame() {
  HeadFrame f;
  f.frankfort = Plane{Vec3::Zero(), Vec3::UnitZ()};
  f.midsagittal = Plane{Vec3::Zero(), Vec3::UnitX()};
  return f;
}

inline Similarity known_similarity() {
  Similarity s;
  s.scale = 1.08;
  s.rotation = Mat3(Eigen::AngleAxisd(0.5, Vec3(0.2, 1.0, -0.3).normalized()));
  s.translation = Vec3(15.0, -30.0, 40.0);
  return s;
}

/// Smooth non-rigid deformation in reference coordinates: a curl-free field (no local rotation, which a
/// near-ellipsoid could not tell from a turn of the whole), gradient below 0.06.
inline Vec3 deform(const Vec3& p) {
  return p + 2.5 * Vec3(std::sin(p.x() / 45.0), std::sin(p.y() / 55.0 + 0.4), std::sin(p.z() / 50.0 - 0.3));
}

/// `mesh` mapped by x -> s(deform(x)) (deformation skipped when `deformed` is false).
inline TriMesh moved(const TriMesh& mesh, const Similarity& s, bool deformed) {
  TriMesh out = mesh;
  for (Vec3& p : out.positions) p = s.apply(deformed ? deform(p) : p);
  out.normals.clear();
  return out;
}

}  // namespace forensim::test
