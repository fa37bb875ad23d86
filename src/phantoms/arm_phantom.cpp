#include "phantoms/arm_phantom.hpp"

#include <cmath>
#include <numbers>

#include "phantoms/sdf.hpp"

namespace forensim {
namespace {

constexpr double wrist_x = 205.0;  // distal end of radius and ulna

// Forearm cross-section half-width (radial-ulnar, y) and half-thickness (dorsal-palmar, z) at x in [0, wrist].
Vec2 forearm_half_axes(double x) {
  const double s = std::clamp(x / wrist_x, 0.0, 1.0);
  const double bulge = std::pow(1.0 - s, 1.6);  // muscle bellies near the elbow
  return Vec2(28.0 + 14.0 * bulge, 18.5 + 15.0 * bulge);
}

double forearm_distance(const Vec3& p) {
  // Tapered elliptical cylinder from x = 0 (a flat cut) to just past the wrist.
  const double x = std::clamp(p.x(), 0.0, wrist_x + 24.0);
  const Vec2 half = forearm_half_axes(x);
  const double centre_z = -1.0 + 2.0 * std::clamp(x / wrist_x, 0.0, 1.0);
  const Vec2 q(p.y() / half.x(), (p.z() - centre_z) / half.y());
  const double radial = (q.norm() - 1.0) * half.minCoeff();
  const double cap_proximal = -p.x();  // the cut end
  const double cap_distal = p.x() - (wrist_x + 24.0);
  // Sharp edge at the cut end, a rounded one where the forearm runs into the palm.
  return std::max(cap_proximal, -sdf::smooth_union(-radial, -cap_distal, 10.0));
}

// Rotates v about the axis by angle (radians), Rodrigues.
Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) {
  return v * std::cos(angle) + axis.cross(v) * std::sin(angle) + axis * axis.dot(v) * (1.0 - std::cos(angle));
}

ArmPhantom::Digit make_finger(const std::string& name, const Vec3& mcp, const Vec3& direction,
                              const std::array<double, 3>& lengths, const std::array<double, 4>& radii,
                              const Vec3& metacarpal_base, double flex_deg) {
  ArmPhantom::Digit d;
  d.name = name;
  d.radii = radii;
  d.metacarpal_base = metacarpal_base;
  d.joints[0] = mcp;
  Vec3 dir = direction.normalized();
  const Vec3 lateral = dir.cross(Vec3::UnitZ()).normalized();  // flexion axis
  const double flex = flex_deg * std::numbers::pi / 180.0;
  for (int s = 0; s < 3; ++s) {
    dir = rotate(dir, lateral, flex);  // relaxed fingers curl slightly toward the palm
    d.joints[s + 1] = d.joints[s] + lengths[s] * dir;
  }
  return d;
}

}  // namespace

ArmPhantom::ArmPhantom() {
  //                       name     MCP joint            direction            lengths (prox, mid, dist)   skin radii
  m_digits.push_back(make_finger("index", Vec3(305, 27, 1), Vec3(1, 0.07, 0), {42, 25, 20}, {9.6, 9.0, 8.2, 7.6},
                                 Vec3(222, 14, 0), 9));
  m_digits.push_back(
      make_finger("middle", Vec3(309, 8, 1), Vec3(1, 0.0, 0), {46, 28, 21}, {9.8, 9.3, 8.4, 7.8}, Vec3(224, 4, 0), 9));
  m_digits.push_back(make_finger("ring", Vec3(304, -11, 1), Vec3(1, -0.06, 0), {43, 27, 21}, {9.3, 8.8, 8.0, 7.4},
                                 Vec3(222, -6, 0), 10));
  m_digits.push_back(make_finger("little", Vec3(294, -29, 0), Vec3(1, -0.13, 0), {34, 20, 18}, {8.4, 7.8, 7.0, 6.6},
                                 Vec3(219, -16, 0), 11));
  // Thumb: CMC joint at the carpus, metacarpal to the MCP joint, then two phalanges (the middle joint is the
  // IP joint; joint 2 repeats it so the chain has the same shape as the fingers).
  Digit thumb;
  thumb.name = "thumb";
  thumb.metacarpal_base = Vec3(224, 20, -6);
  thumb.joints = {Vec3(262, 50, -13), Vec3(292, 63, -15), Vec3(292, 63, -15), Vec3(316, 71, -14)};
  thumb.radii = {11.5, 10.2, 10.2, 9.0};
  m_digits.push_back(thumb);
  m_part_names = {"forearm", "wrist", "palm", "thumb", "index", "middle", "ring", "little"};
}

BoundingBox ArmPhantom::bounds() const {
  BoundingBox box;
  box.extend(Vec3(-2, -48, -38));
  box.extend(Vec3(400, 90, 38));
  return box;
}

double ArmPhantom::skin_distance(const Vec3& p) const {
  using namespace sdf;
  double d = forearm_distance(p);
  // Palm: a flattened rounded box, wider toward the knuckles, with thenar and hypothenar eminences.
  const double palm = smooth_union(rounded_box(p, Vec3(262, -1, -1), Vec3(44, 38, 12.0), 11.0),
                                   ellipsoid(p, Vec3(252, 0, -1), Vec3(50, 40, 15)), 10.0);
  d = smooth_union(d, palm, 22.0);
  d = smooth_union(d, ellipsoid(p, Vec3(246, 32, -9), Vec3(34, 20, 14)), 10.0);  // thenar
  d = smooth_union(d, ellipsoid(p, Vec3(254, -29, -7), Vec3(34, 12, 11)), 9.0);  // hypothenar
  for (const Digit& digit : m_digits) {
    const bool is_thumb = digit.name == "thumb";
    // Web between the digits and the palm: the proximal segment blends into the palm.
    const Vec3 web = is_thumb ? Vec3(digit.metacarpal_base + Vec3(10, 8, -2)) : Vec3(digit.joints[0] - Vec3(14, 0, 0));
    double f = capsule(p, web, digit.joints[0], digit.radii[0] + 1.0, digit.radii[0]);
    for (int s = 0; s < 3; ++s) {
      if (digit.joints[s] == digit.joints[s + 1]) continue;
      f = smooth_union(f, capsule(p, digit.joints[s], digit.joints[s + 1], digit.radii[s], digit.radii[s + 1]), 2.0);
    }
    // Knuckles: dorsal bumps over the joints.
    for (int s = 0; s < 3; ++s) {
      if (s > 0 && digit.joints[s] == digit.joints[s - 1]) continue;
      f = smooth_union(f, sphere(p, digit.joints[s] + Vec3(0, 0, 0.3 * digit.radii[s]), 0.72 * digit.radii[s]), 4.0);
    }
    // Finger pad: a palmar bulge on the distal phalanx.
    const Vec3 pad = digit.joints[2] + 0.55 * (digit.joints[3] - digit.joints[2]) - Vec3(0, 0, 0.35 * digit.radii[3]);
    f = smooth_union(f, ellipsoid(p, pad, Vec3(0.9, 0.8, 0.6) * digit.radii[3]), 3.0);
    d = smooth_union(d, f, is_thumb ? 9.0 : 5.0);
  }
  return d;
}

double ArmPhantom::bone_distance(const Vec3& p) const {
  using namespace sdf;
  // Radius (thumb side, wide distally) and ulna (little-finger side, wide proximally).
  double d = capsule(p, Vec3(4, 13, 0), Vec3(wrist_x - 8, 14, 0), 6.5, 9.0);
  d = smooth_union(d, ellipsoid(p, Vec3(wrist_x - 6, 11, 0), Vec3(9, 13, 9)), 5.0);  // distal radius flare
  d = smooth_union(d, capsule(p, Vec3(4, -17, 2), Vec3(wrist_x - 6, -17, 1), 9.0, 5.5), 2.0);
  d = smooth_union(d, sphere(p, Vec3(wrist_x - 4, -18, 1), 6.0), 2.0);  // ulnar head
  // Carpal block.
  d = smooth_union(d, rounded_box(p, Vec3(wrist_x + 11, 0, 0), Vec3(10, 24, 8), 5.0), 2.0);
  for (const Digit& digit : m_digits) {
    const Vec3 base_dir = (digit.joints[0] - digit.metacarpal_base).normalized();
    // Metacarpal shaft and head, ending 2 mm short of the joint centre.
    d = std::min(d, capsule(p, digit.metacarpal_base, digit.joints[0] - 5.5 * base_dir, 3.8, 3.5));
    d = std::min(d, sphere(p, digit.joints[0] - 5.0 * base_dir, 4.6));
    // Phalanges with 1.5 mm joint gaps.
    const double bone_radius[3] = {3.6, 3.0, 2.5};
    for (int s = 0; s < 3; ++s) {
      if (digit.joints[s] == digit.joints[s + 1]) continue;
      const Vec3 dir = (digit.joints[s + 1] - digit.joints[s]).normalized();
      const double tip_margin = s == 2 ? 3.5 : 1.5;
      d = std::min(d, capsule(p, digit.joints[s] + 1.5 * dir, digit.joints[s + 1] - tip_margin * dir,
                              bone_radius[s] * (digit.name == "thumb" ? 1.2 : 1.0), bone_radius[s] * 0.9));
    }
  }
  return std::max(d, 3.0 - p.x());  // bones end 3 mm inside the cut end
}

int ArmPhantom::part_at(const Vec3& p) const {
  // Digits first: a point beyond a digit's base joint and near its axis belongs to it.
  int best = -1;
  double best_distance = 1e9;
  for (std::size_t i = 0; i < m_digits.size(); ++i) {
    const Digit& digit = m_digits[i];
    const Vec3 axis = (digit.joints[1] - digit.joints[0]).normalized();
    if ((p - digit.joints[0]).dot(axis) < -4.0) continue;
    double dist = 1e9;
    for (int s = 0; s < 3; ++s) {
      dist = std::min(dist, sdf::capsule(p, digit.joints[s], digit.joints[s + 1], digit.radii[s], digit.radii[s + 1]));
    }
    if (dist < 4.0 && dist < best_distance) {
      best_distance = dist;
      best = static_cast<int>(i);
    }
  }
  if (best >= 0) {
    const std::string& name = m_digits[static_cast<std::size_t>(best)].name;
    for (std::size_t k = 0; k < m_part_names.size(); ++k) {
      if (m_part_names[k] == name) return static_cast<int>(k);
    }
  }
  if (p.x() < wrist_x - 20.0) return 0;  // forearm
  if (p.x() < wrist_x + 8.0) return 1;   // wrist
  return 2;                              // palm
}

}  // namespace forensim
