#include "spatial/self_intersection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/parallel.hpp"
#include "geometry/mesh_topology.hpp"
#include "spatial/ray_caster.hpp"

namespace forensim {

std::size_t self_intersection_count(const TriMesh& mesh, double relative_margin) {
  TriMesh bare;  // positions and triangles only: other attributes do not matter here
  bare.positions = mesh.positions;
  bare.triangles = mesh.triangles;
  const RayCaster caster(bare);
  const std::vector<std::array<Index, 2>> edges = unique_edges(mesh.triangles);
  const double margin = std::clamp(relative_margin, 0.0, 0.49);
  const double total = parallel_sum(0, edges.size(), [&](std::size_t e) {
    const Index a = edges[e][0], b = edges[e][1];
    const Vec3& p = mesh.positions[static_cast<std::size_t>(a)];
    const Vec3 d = mesh.positions[static_cast<std::size_t>(b)] - p;
    if (!(d.squaredNorm() > 0.0)) return 0.0;
    // The segment p + t d, t in (margin, 1 - margin): walk its hits in t, skipping triangles that touch the edge.
    double t_min = margin;
    const double t_max = 1.0 - margin;
    double crossings = 0.0;
    for (int guard = 0; guard < 64 && t_min <= t_max; ++guard) {
      const std::optional<RayHit> hit = caster.intersect(p, d, t_min, t_max);
      if (!hit) break;
      const Tri& tri = mesh.triangles[static_cast<std::size_t>(hit->triangle)];
      const bool touches =
          std::find(tri.begin(), tri.end(), a) != tri.end() || std::find(tri.begin(), tri.end(), b) != tri.end();
      if (!touches) crossings += 1.0;
      // The hit's t is refined in double and may fall a rounding step below t_min: always move forward.
      t_min = std::nextafter(std::max(hit->t, t_min), std::numeric_limits<double>::infinity());
    }
    return crossings;
  });
  return static_cast<std::size_t>(total + 0.5);
}

}  // namespace forensim
