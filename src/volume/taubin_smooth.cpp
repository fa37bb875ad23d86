#include "volume/taubin_smooth.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/vertex_neighbours.hpp"

namespace forensim {

void taubin_smooth(TriMesh& mesh, int iterations, double lambda, double mu) {
  require_input(iterations >= 0, "taubin_smooth", "iterations", "must not be negative");
  require_input(std::isfinite(lambda) && lambda > 0.0, "taubin_smooth", "lambda", "must be positive");
  require_input(std::isfinite(mu) && mu < 0.0, "taubin_smooth", "mu", "must be negative");
  if (iterations == 0 || mesh.positions.empty()) return;
  const std::size_t n = mesh.positions.size();
  const VertexNeighbours adjacency = vertex_neighbours(mesh.triangles, n);
  const std::vector<std::size_t>& start = adjacency.start;
  const std::vector<Index>& neighbours = adjacency.index;
  std::vector<Vec3> next(n);
  const auto step = [&](double factor) {
    parallel_for_chunks(0, n, [&](std::size_t b, std::size_t e) {
      for (std::size_t v = b; v < e; ++v) {
        const std::size_t deg = start[v + 1] - start[v];
        if (deg == 0) {
          next[v] = mesh.positions[v];
          continue;
        }
        Vec3 mean = Vec3::Zero();
        for (std::size_t k = start[v]; k < start[v + 1]; ++k) mean += mesh.positions[std::size_t(neighbours[k])];
        mean /= double(deg);
        next[v] = mesh.positions[v] + factor * (mean - mesh.positions[v]);
      }
    });
    mesh.positions.swap(next);
  };
  for (int it = 0; it < iterations; ++it) {
    step(lambda);
    step(mu);
  }
  if (mesh.has_normals()) compute_normals(mesh);
}

}  // namespace forensim
