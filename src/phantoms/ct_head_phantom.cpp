#include "phantoms/ct_head_phantom.hpp"

#include <cmath>

#include "core/parallel.hpp"
#include "core/random.hpp"
#include "phantoms/sdf.hpp"

namespace forensim {
namespace {

// Proportions of an adult head (mm): head breadth ~150, length ~195, height ~230 with the neck.
double mirror_x(double x) {
  return std::abs(x);
}

}  // namespace

double ct_phantom_skin_distance(const Vec3& p) {
  using namespace sdf;
  const Vec3 q(mirror_x(p.x()), p.y(), p.z());                                       // bilateral symmetry
  double d = ellipsoid(p, Vec3(0, 8, 40), Vec3(76, 98, 92));                         // cranium
  d = smooth_union(d, ellipsoid(p, Vec3(0, -30, -18), Vec3(60, 62, 62)), 18);        // face and jaw mass
  d = smooth_union(d, ellipsoid(p, Vec3(0, -36, -50), Vec3(62, 52, 38)), 12);        // jaw
  d = smooth_union(d, capsule(p, Vec3(0, 12, -60), Vec3(0, 18, -130), 52, 56), 20);  // neck
  d = smooth_union(d, capsule(p, Vec3(0, -86, 6), Vec3(0, -102, -22), 7, 11), 8);    // nose
  d = smooth_union(d, ellipsoid(p, Vec3(0, -84, -46), Vec3(22, 10, 7)), 6);          // lips
  d = smooth_union(d, ellipsoid(p, Vec3(0, -74, -78), Vec3(20, 14, 14)), 10);        // chin
  d = smooth_union(d, ellipsoid(q, Vec3(74, 14, 4), Vec3(9, 22, 30)), 6);            // ears
  d = smooth_subtract(d, ellipsoid(q, Vec3(32, -84, 18), Vec3(17, 10, 11)), 8);      // eye hollows
  d = smooth_union(d, ellipsoid(q, Vec3(32, -80, 17), Vec3(14, 7, 9)), 4);           // closed lids
  return d;
}

double ct_phantom_bone_distance(const Vec3& p) {
  using namespace sdf;
  const Vec3 q(mirror_x(p.x()), p.y(), p.z());
  // Cranial vault: a 7 mm shell under the scalp.
  const double vault_outer = ellipsoid(p, Vec3(0, 10, 44), Vec3(69, 90, 84));
  double d = shell(vault_outer + 3.5, 7.0);
  d = std::max(d, -(p.z() + 6.0 - 0.25 * (p.y() + 60)));  // open skull base toward the face
  // Facial skeleton: maxilla block, zygomatic arches, mandible arc.
  d = smooth_union(d, rounded_box(p, Vec3(0, -62, -22), Vec3(30, 14, 16), 8), 6);     // maxilla
  d = smooth_union(d, capsule(q, Vec3(44, -56, 6), Vec3(62, 0, 2), 5, 4), 5);         // zygomatic arch
  d = smooth_union(d, capsule(q, Vec3(20, -62, -58), Vec3(38, -14, -46), 5, 6), 5);   // mandible body
  d = smooth_union(d, capsule(q, Vec3(38, -14, -46), Vec3(42, 0, -12), 6, 5), 5);     // ramus
  d = smooth_union(d, capsule(p, Vec3(-20, -62, -58), Vec3(20, -62, -58), 6, 6), 5);  // chin arc
  d = smooth_union(d, capsule(p, Vec3(0, -68, 20), Vec3(0, -74, -6), 5, 4), 4);       // nasal bones
  d = smooth_subtract(d, ellipsoid(q, Vec3(32, -66, 18), Vec3(17, 20, 15)), 3);       // orbits
  d = smooth_subtract(d, ellipsoid(p, Vec3(0, -76, -6), Vec3(11, 12, 13)), 3);        // nasal aperture
  // Cervical spine.
  d = smooth_union(d, capsule(p, Vec3(0, 26, -30), Vec3(0, 30, -140), 11, 12), 4);
  return d;
}

ScalarGrid make_ct_head_phantom(const CtHeadPhantomOptions& options) {
  const double h = options.voxel_mm > 0 ? options.voxel_mm : 2.0;
  const Vec3 lo(-100, -125, -150), hi(100, 125, 150);
  const int nx = static_cast<int>(std::ceil((hi.x() - lo.x()) / h)) + 1;
  const int ny = static_cast<int>(std::ceil((hi.y() - lo.y()) / h)) + 1;
  const int nz = static_cast<int>(std::ceil((hi.z() - lo.z()) / h)) + 1;
  ScalarGrid grid = ScalarGrid::filled(nx, ny, nz, 0.0f);
  grid.spacing = Vec3::Constant(h);
  grid.origin = lo;
  // Partial-volume edges: each boundary blurs over about one voxel.
  auto edge = [h](double distance) { return 1.0 / (1.0 + std::exp(distance / (0.35 * h))); };
  parallel_for(
      0, static_cast<std::size_t>(nz),
      [&](std::size_t k) {
        for (int j = 0; j < ny; ++j) {
          for (int i = 0; i < nx; ++i) {
            const Vec3 p = lo + Vec3(i * h, j * h, static_cast<double>(k) * h);
            const double skin = edge(ct_phantom_skin_distance(p));
            const double bone = edge(std::max(ct_phantom_bone_distance(p), ct_phantom_skin_distance(p) + 2.0));
            double value = 1000.0 * skin + 800.0 * bone;
            value +=
                options.noise_hu * RandomStream(options.seed, grid.linear_index(i, j, static_cast<int>(k))).normal();
            grid.at(i, j, static_cast<int>(k)) = static_cast<float>(std::max(0.0, value));
          }
        }
      },
      1);
  return grid;
}

}  // namespace forensim
