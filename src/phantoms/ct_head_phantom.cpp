#include "phantoms/ct_head_phantom.hpp"

#include <cmath>

#include "core/parallel.hpp"
#include "core/random.hpp"
#include "phantoms/head_phantom.hpp"

namespace forensim {
double ct_phantom_skin_distance(const Vec3& p) {
  static const HeadPhantom head;
  return head.skin_distance(p);
}

double ct_phantom_bone_distance(const Vec3& p) {
  static const HeadPhantom head;
  return head.bone_distance(p);
}

ScalarGrid make_ct_head_phantom(const CtHeadPhantomOptions& options) {
  const double h = options.voxel_mm > 0 ? options.voxel_mm : 2.0;
  const Vec3 lo(-100, -125, -152), hi(100, 115, 150);
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
