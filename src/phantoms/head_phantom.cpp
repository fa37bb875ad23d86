#include "phantoms/head_phantom.hpp"

#include <cmath>

#include "phantoms/sdf.hpp"

namespace forensim {
namespace {

// Mirrors x so bilateral features are modelled once, on the patient's left (x > 0).
Vec3 mirrored(const Vec3& p) {
  return Vec3(std::abs(p.x()), p.y(), p.z());
}

constexpr double neck_bottom_z = -150.0;

/// The teeth (in mirrored coordinates) and the cervical spine: primitives joined by a plain minimum, so a group
/// whose box lies farther than the distance so far cannot change it and is skipped (bone_distance runs millions of
/// times when the template's skull is sampled). Each box bounds its group's shapes: a rounded box's distance
/// and a capsule's (ra + (rb - ra) h, at most the larger radius, below the distance to the axis) are at least
/// the distance to a box holding the shape.
struct MinGroups {
  static constexpr int tooth_count = 8;
  Vec3 tooth_centre[2][tooth_count];
  BoundingBox teeth, spine;

  MinGroups() {
    const Vec3 tooth_half(3.2, 3.0, 4.2);
    for (int row = 0; row < 2; ++row) {
      const double z = row == 0 ? -39.0 : -47.0;
      for (int t = 0; t < tooth_count; ++t) {
        const double angle = (t + 0.5) / 8.0 * 1.35;  // radians from the midline
        tooth_centre[row][t] = Vec3(std::sin(angle) * 24.0, -78.0 + (1.0 - std::cos(angle)) * 34.0, z);
        teeth.extend(tooth_centre[row][t] - tooth_half);
        teeth.extend(tooth_centre[row][t] + tooth_half);
      }
    }
    for (int v = 0; v < 7; ++v) {
      const double z = -34.0 - v * 16.0;
      spine.extend(Vec3(0, 24 + v * 0.8, z) - Vec3(9, 8, 6.2));
      spine.extend(Vec3(0, 24 + v * 0.8, z) + Vec3(9, 8, 6.2));
      spine.extend(Vec3(0, 30 + v * 0.8, z) - Vec3::Constant(3.5));
      spine.extend(Vec3(0, 30 + v * 0.8, z) + Vec3::Constant(3.5));
      spine.extend(Vec3(0, 44 + v, z - 3) - Vec3::Constant(3.5));
      spine.extend(Vec3(0, 44 + v, z - 3) + Vec3::Constant(3.5));
    }
  }
};

const MinGroups& min_groups() {
  static const MinGroups groups;
  return groups;
}

/// True when every shape inside `box` lies farther from p than d (with a margin far above rounding), so that
/// min(d, shape) is d for all of them: p lies outside the box, farther than d.
bool beyond(const BoundingBox& box, const Vec3& p, double d) {
  const Vec3 gap = (box.min - p).cwiseMax(p - box.max);
  if (gap.maxCoeff() <= 0.0) return false;  // inside the box: a shape may hold p
  return gap.cwiseMax(0.0).norm() > d + 1e-6;
}

}  // namespace

HeadPhantom::HeadPhantom() {
  m_part_names = {"scalp", "forehead", "eyes", "nose", "cheeks", "lips", "chin", "ears", "neck"};
}

BoundingBox HeadPhantom::bounds() const {
  BoundingBox box;
  box.extend(Vec3(-95, -122, neck_bottom_z - 1));
  box.extend(Vec3(95, 112, 146));
  return box;
}

double HeadPhantom::skin_distance(const Vec3& p) const {
  using namespace sdf;
  const Vec3 q = mirrored(p);
  double d = ellipsoid(p, Vec3(0, 10, 50), Vec3(75, 98, 92));                           // cranium
  d = smooth_union(d, ellipsoid(p, Vec3(0, -40, -6), Vec3(60, 54, 64)), 20.0);          // face mass
  d = smooth_union(d, ellipsoid(p, Vec3(0, -36, -50), Vec3(60, 52, 36)), 14.0);         // jaw
  d = smooth_union(d, ellipsoid(q, Vec3(44, -62, -4), Vec3(22, 14, 20)), 10.0);         // cheeks
  d = smooth_union(d, capsule(q, Vec3(8, -88, 31), Vec3(42, -80, 33), 7.5, 6.0), 8.0);  // brow ridge
  d = smooth_union(d, ellipsoid(q, Vec3(40, -66, 20), Vec3(22, 16, 17)), 8.0);          // lateral orbit and temple
  // Eye sockets with closed lids over the eyeballs.
  d = smooth_subtract(d, ellipsoid(q, Vec3(32, -94, 19), Vec3(16, 12, 10.5)), 7.0);
  d = smooth_union(d, ellipsoid(q, Vec3(33, -83, 19), Vec3(12.5, 5.5, 7.5)), 4.0);
  // Nose: bridge, tip, alae.
  d = smooth_union(d, capsule(p, Vec3(0, -88, 24), Vec3(0, -108, -8), 5.5, 8.5), 6.0);
  d = smooth_union(d, sphere(p, Vec3(0, -105, -11), 9.0), 4.0);
  d = smooth_union(d, sphere(q, Vec3(12, -95, -15), 7.0), 4.0);
  d = smooth_subtract(d, ellipsoid(q, Vec3(6, -101, -22), Vec3(3.5, 5, 2.2)), 1.5);  // nostrils
  // Lips with a mouth slit, chin.
  d = smooth_union(d, ellipsoid(p, Vec3(0, -90, -37), Vec3(22, 8.5, 6.5)), 5.0);
  d = smooth_union(d, ellipsoid(p, Vec3(0, -87, -49), Vec3(19, 8.5, 6.5)), 5.0);
  d = smooth_subtract(d, rounded_box(p, Vec3(0, -97, -43.5), Vec3(21, 8, 0.6), 0.5), 1.2);
  d = smooth_union(d, ellipsoid(p, Vec3(0, -78, -74), Vec3(20, 12, 13)), 10.0);
  // Ears with a hollow concha.
  double ear = ellipsoid(q, Vec3(76, 10, 10), Vec3(7, 17, 29));
  ear = smooth_subtract(ear, ellipsoid(q, Vec3(82, 8, 4), Vec3(4.5, 9, 13)), 2.0);
  d = smooth_union(d, ear, 5.0);
  // Neck, cut flat at the bottom.
  d = smooth_union(d, capsule(p, Vec3(0, 12, -55), Vec3(0, 18, neck_bottom_z - 40), 52, 56), 24.0);
  return std::max(d, neck_bottom_z - p.z());
}

double HeadPhantom::bone_distance(const Vec3& p) const {
  using namespace sdf;
  const Vec3 q = mirrored(p);
  // Cranial vault: a 7 mm shell 5 mm under the scalp, open below toward the face and skull base.
  const double vault = shell(ellipsoid(p, Vec3(0, 12, 52), Vec3(69, 91, 85)) + 3.5, 7.0);
  double d = std::max(vault, -(p.z() - 10.0 + 0.23 * (p.y() + 80.0)));
  d = smooth_union(d, capsule(q, Vec3(6, -80, 30), Vec3(40, -74, 31), 6.0, 5.0), 4.0);  // supraorbital ridge
  // Orbits: rims around hollows.
  d = smooth_union(d, shell(ellipsoid(q, Vec3(32, -68, 18), Vec3(16.5, 12, 15)), 5.0), 3.0);
  d = smooth_subtract(d, ellipsoid(q, Vec3(32, -73, 18), Vec3(14, 16, 12.5)), 2.0);
  // Zygomatic bone and arch.
  d = smooth_union(d, ellipsoid(q, Vec3(45, -64, 4), Vec3(11.5, 9, 10)), 4.0);
  d = smooth_union(d, capsule(q, Vec3(48, -54, 2), Vec3(57, 0, 4), 4.5, 3.5), 4.0);
  // Maxilla with the nasal aperture; nasal bones.
  d = smooth_union(d, rounded_box(p, Vec3(0, -62, -20), Vec3(28, 16, 17), 9.0), 6.0);
  d = smooth_subtract(d, ellipsoid(p, Vec3(0, -80, -4), Vec3(11, 14, 14)), 3.0);
  d = smooth_union(d, capsule(p, Vec3(0, -76, 24), Vec3(0, -86, 4), 4.5, 3.5), 3.0);
  // Teeth: upper and lower rows along the dental arch.
  const MinGroups& groups = min_groups();
  if (!beyond(groups.teeth, q, d)) {
    for (const auto& row : groups.tooth_centre) {
      for (const Vec3& centre : row) d = std::min(d, rounded_box(q, centre, Vec3(3.2, 3.0, 4.2), 1.5));
    }
  }
  // Mandible: body, chin, rami.
  d = smooth_union(d, capsule(q, Vec3(20, -70, -60), Vec3(38, -16, -50), 6.0, 6.5), 5.0);
  d = smooth_union(d, capsule(q, Vec3(38, -16, -50), Vec3(42, 2, -12), 6.0, 5.0), 5.0);
  d = smooth_union(d, capsule(p, Vec3(-20, -70, -60), Vec3(20, -70, -60), 6.5, 6.5), 5.0);
  d = smooth_union(d, ellipsoid(p, Vec3(0, -68, -52), Vec3(14, 6, 10)), 4.0);  // alveolar part under the teeth
  // Cervical spine: seven vertebral bodies with discs between them.
  if (beyond(groups.spine, p, d)) return d;
  for (int v = 0; v < 7; ++v) {
    const double z = -34.0 - v * 16.0;
    d = std::min(d, rounded_box(p, Vec3(0, 24 + v * 0.8, z), Vec3(9, 8, 6.2), 3.0));
    d = std::min(d, capsule(p, Vec3(0, 30 + v * 0.8, z), Vec3(0, 44 + v, z - 3), 3.5, 3.0));  // spinous process
  }
  return d;
}

int HeadPhantom::part_at(const Vec3& p) const {
  const Vec3 q = mirrored(p);
  if (p.z() < -88.0 || (p.z() < -60.0 && p.y() > -30.0)) return 8;                               // neck
  if (q.x() > 66.0 && std::abs(p.y() - 10.0) < 24.0 && std::abs(p.z() - 10.0) < 34.0) return 7;  // ears
  if (p.y() < -60.0) {
    if (p.z() > 28.0) return 1;                                                    // forehead
    if (q.x() < 16.0 && p.z() > -28.0 && p.z() < 28.0 && p.y() < -84.0) return 3;  // nose
    if (p.z() > 6.0 && q.x() > 14.0) return 2;                                     // eyes
    if (p.z() < -30.0 && p.z() > -56.0 && q.x() < 28.0) return 5;                  // lips
    if (p.z() <= -56.0) return 6;                                                  // chin
    return 4;                                                                      // cheeks
  }
  return 0;  // scalp
}

}  // namespace forensim
