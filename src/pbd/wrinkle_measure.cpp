#include "pbd/wrinkle_measure.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "pbd/bending_constraint.hpp"

namespace forensim {

WrinkleMeasure wrinkle_measure(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles,
                               int smoothing_steps, const std::vector<std::uint8_t>& vertex_mask) {
  const std::size_t n = positions.size();
  require_input(vertex_mask.empty() || vertex_mask.size() == n, "wrinkle measure", "vertex mask",
                "has " + std::to_string(vertex_mask.size()) + " entries for " + std::to_string(n) + " vertices");
  require_input(smoothing_steps >= 0, "wrinkle measure", "smoothing steps", "must be non-negative");
  auto in = [&](Index v) { return vertex_mask.empty() || vertex_mask[static_cast<std::size_t>(v)] != 0; };
  const BendingConstraints pairs = make_bending_constraints(positions, triangles, "wrinkle measure mesh");
  const std::vector<std::array<Index, 2>> edges = unique_edges(triangles);

  // Uniform-Laplacian neighbourhoods (CSR).
  std::vector<Index> offsets(n + 1, 0), neighbours;
  for (const auto& e : edges) {
    ++offsets[static_cast<std::size_t>(e[0]) + 1];
    ++offsets[static_cast<std::size_t>(e[1]) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) offsets[i + 1] += offsets[i];
  neighbours.resize(static_cast<std::size_t>(offsets[n]));
  std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
  for (const auto& e : edges) {
    neighbours[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[0])]++)] = e[1];
    neighbours[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[1])]++)] = e[0];
  }
  std::vector<Vec3> smooth = positions, next(n);
  auto pass = [&](double factor) {
    parallel_for(0, n, [&](std::size_t i) {
      const Index lo = offsets[i], hi = offsets[i + 1];
      if (hi == lo) {
        next[i] = smooth[i];
        return;
      }
      Vec3 mean = Vec3::Zero();
      for (Index k = lo; k < hi; ++k) mean += smooth[static_cast<std::size_t>(neighbours[static_cast<std::size_t>(k)])];
      mean /= static_cast<double>(hi - lo);
      next[i] = smooth[i] + factor * (mean - smooth[i]);
    });
    smooth.swap(next);
  };
  for (int s = 0; s < smoothing_steps; ++s) {
    pass(0.5);
    pass(-0.53);
  }
  WrinkleMeasure out;
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!in(static_cast<Index>(i))) continue;
    sum += (positions[i] - smooth[i]).squaredNorm();
    ++count;
  }
  out.rms_smooth_distance_mm = count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;

  double area = 0.0, curvature = 0.0;
  for (const Tri& t : triangles) {
    if (!(in(t[0]) && in(t[1]) && in(t[2]))) continue;
    const Vec3& a = positions[static_cast<std::size_t>(t[0])];
    area += 0.5 *
            (positions[static_cast<std::size_t>(t[1])] - a).cross(positions[static_cast<std::size_t>(t[2])] - a).norm();
  }
  for (const auto& q : pairs.quad_vertices) {
    if (!(in(q[0]) && in(q[1]) && in(q[2]) && in(q[3]))) continue;
    const Quad x{positions[static_cast<std::size_t>(q[0])], positions[static_cast<std::size_t>(q[1])],
                 positions[static_cast<std::size_t>(q[2])], positions[static_cast<std::size_t>(q[3])]};
    curvature += std::abs(dihedral_angle(x)) * (x[3] - x[2]).norm();
  }
  out.mean_abs_curvature_per_mm = area > 0.0 ? curvature / (2.0 * area) : 0.0;
  return out;
}

double wrinkle_height_mm(const std::vector<Vec3>& positions, const std::vector<Vec3>& reference,
                         const std::vector<Tri>& triangles, int smoothing_steps,
                         const std::vector<std::uint8_t>& vertex_mask) {
  require_input(reference.size() == positions.size(), "wrinkle height", "reference",
                "has " + std::to_string(reference.size()) + " vertices for " + std::to_string(positions.size()));
  TriMesh glued;
  glued.positions = reference;
  glued.triangles = triangles;
  const std::vector<Vec3> normals = vertex_normals(glued);
  std::vector<Vec3> lift(positions.size());
  for (std::size_t i = 0; i < lift.size(); ++i) lift[i] = (positions[i] - reference[i]).dot(normals[i]) * normals[i];
  return wrinkle_measure(lift, triangles, smoothing_steps, vertex_mask).rms_smooth_distance_mm;
}

}  // namespace forensim
