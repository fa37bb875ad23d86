#include "pbd/wrinkle_measure.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "pbd/bending_constraint.hpp"

namespace forensim {

namespace {

/// `positions` after `steps` Taubin steps (lambda 0.5, mu -0.53) of the uniform Laplacian over the edges of
/// `triangles`.
std::vector<Vec3> taubin_smoothed(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles, int steps) {
  const std::size_t n = positions.size();
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
  for (int s = 0; s < steps; ++s) {
    pass(0.5);
    pass(-0.53);
  }
  return smooth;
}

void check_indices(const std::vector<Tri>& triangles, std::size_t n, const std::string& source) {
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (Index v : triangles[t])
      if (v < 0 || static_cast<std::size_t>(v) >= n)
        throw InputError(source, "triangle " + std::to_string(t),
                         "has vertex " + std::to_string(v) + " outside the " + std::to_string(n) + " vertices");
}

}  // namespace

WrinkleMeasure wrinkle_measure(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles,
                               int smoothing_steps, const std::vector<std::uint8_t>& vertex_mask) {
  const std::size_t n = positions.size();
  require_input(vertex_mask.empty() || vertex_mask.size() == n, "wrinkle measure", "vertex mask",
                "has " + std::to_string(vertex_mask.size()) + " entries for " + std::to_string(n) + " vertices");
  require_input(smoothing_steps >= 0, "wrinkle measure", "smoothing steps", "must be non-negative");
  auto in = [&](Index v) { return vertex_mask.empty() || vertex_mask[static_cast<std::size_t>(v)] != 0; };
  const BendingConstraints pairs = make_bending_constraints(positions, triangles, "wrinkle measure mesh");
  const std::vector<Vec3> smooth = taubin_smoothed(positions, triangles, smoothing_steps);
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

namespace {

/// The fine lift-off vectors f_i and the reference's vertex normals n_i (see wrinkle_size), after the checks.
struct FineLiftOff {
  std::vector<Vec3> fine, normals;
};

FineLiftOff fine_lift_off(const std::vector<Vec3>& positions, const std::vector<Vec3>& reference,
                          const std::vector<Tri>& triangles, int smoothing_steps,
                          const std::vector<std::uint8_t>& vertex_mask, const std::string& source) {
  const std::size_t n = positions.size();
  require_input(reference.size() == n, source, "reference",
                "has " + std::to_string(reference.size()) + " vertices for " + std::to_string(n));
  require_input(vertex_mask.empty() || vertex_mask.size() == n, source, "vertex mask",
                "has " + std::to_string(vertex_mask.size()) + " entries for " + std::to_string(n) + " vertices");
  require_input(smoothing_steps >= 0, source, "smoothing steps", "must be non-negative");
  check_indices(triangles, n, source);
  TriMesh glued;
  glued.positions = reference;
  glued.triangles = triangles;
  FineLiftOff out;
  out.normals = vertex_normals(glued);
  std::vector<Vec3> lift(n);
  for (std::size_t i = 0; i < n; ++i) lift[i] = (positions[i] - reference[i]).dot(out.normals[i]) * out.normals[i];
  const std::vector<Vec3> smooth = taubin_smoothed(lift, triangles, smoothing_steps);
  out.fine.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.fine[i] = lift[i] - smooth[i];
  return out;
}

}  // namespace

std::vector<double> wrinkle_lift_off_mm(const std::vector<Vec3>& positions, const std::vector<Vec3>& reference,
                                        const std::vector<Tri>& triangles, int smoothing_steps) {
  const FineLiftOff f = fine_lift_off(positions, reference, triangles, smoothing_steps, {}, "wrinkle lift-off");
  std::vector<double> h(positions.size());
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = f.fine[i].dot(f.normals[i]);
  return h;
}

WrinkleSize wrinkle_size(const std::vector<Vec3>& positions, const std::vector<Vec3>& reference,
                         const std::vector<Tri>& triangles, int smoothing_steps,
                         const std::vector<std::uint8_t>& vertex_mask) {
  const std::size_t n = positions.size();
  const FineLiftOff f = fine_lift_off(positions, reference, triangles, smoothing_steps, vertex_mask, "wrinkle size");
  auto in = [&](Index v) { return vertex_mask.empty() || vertex_mask[static_cast<std::size_t>(v)] != 0; };
  std::vector<double> h(n);
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    h[i] = f.fine[i].dot(f.normals[i]);
    if (!in(static_cast<Index>(i))) continue;
    sum += f.fine[i].squaredNorm();
    ++count;
  }
  WrinkleSize out;
  out.height_mm = count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
  // Integrals of h^2 and |grad h|^2 of the piecewise-linear height over the reference triangles.
  double h2 = 0.0, g2 = 0.0;
  for (const Tri& t : triangles) {
    if (!(in(t[0]) && in(t[1]) && in(t[2]))) continue;
    const auto a = static_cast<std::size_t>(t[0]), b = static_cast<std::size_t>(t[1]),
               c = static_cast<std::size_t>(t[2]);
    const Vec3 normal = (reference[b] - reference[a]).cross(reference[c] - reference[a]);
    const double twice_area = normal.norm();
    if (!(twice_area > 0.0)) continue;
    // grad phi_a = n x (c - b) / 2A and so on, with n the unit normal.
    const Vec3 gradient = normal.cross(h[a] * (reference[c] - reference[b]) + h[b] * (reference[a] - reference[c]) +
                                       h[c] * (reference[b] - reference[a])) /
                          (twice_area * twice_area);
    const double area = 0.5 * twice_area;
    g2 += area * gradient.squaredNorm();
    h2 += area / 6.0 * (h[a] * h[a] + h[b] * h[b] + h[c] * h[c] + h[a] * h[b] + h[b] * h[c] + h[c] * h[a]);
  }
  constexpr double two_pi = 6.283185307179586;
  out.wavelength_mm = g2 > 0.0 ? two_pi * std::sqrt(h2 / g2) : 0.0;
  return out;
}

double wrinkle_height_mm(const std::vector<Vec3>& positions, const std::vector<Vec3>& reference,
                         const std::vector<Tri>& triangles, int smoothing_steps,
                         const std::vector<std::uint8_t>& vertex_mask) {
  return wrinkle_size(positions, reference, triangles, smoothing_steps, vertex_mask).height_mm;
}

}  // namespace forensim
