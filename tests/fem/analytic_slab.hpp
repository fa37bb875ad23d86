#pragma once
/// Series solution of 1D diffusion in a slab 0 <= x <= L, insulated at x = 0, Robin -D u_x = h (u - u_a) at
/// x = L, uniform start u_0 (Crank, "The mathematics of diffusion", eq. 4.52 form):
///   (u - u_a) / (u_0 - u_a) = sum_n C_n cos(beta_n x / L) exp(-beta_n^2 D t / L^2),
///   beta_n tan beta_n = Bi = h L / D,   C_n = 4 sin beta_n / (2 beta_n + sin 2 beta_n).
/// Test helper, with the box-slab mesh used by the diffusion tests.

#include <cmath>
#include <numbers>
#include <vector>

#include "fem/diffusion_solver.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_boundary.hpp"

namespace forensim::test {

class SlabSeries {
 public:
  SlabSeries(double biot, int terms) {
    for (int n = 0; n < terms; ++n) {
      double lo = n * std::numbers::pi + 1e-14;
      double hi = n * std::numbers::pi + 0.5 * std::numbers::pi - 1e-14;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (mid * std::tan(mid) < biot ? lo : hi) = mid;
      }
      const double b = 0.5 * (lo + hi);
      m_beta.push_back(b);
      m_coef.push_back(4.0 * std::sin(b) / (2.0 * b + std::sin(2.0 * b)));
    }
  }
  /// Dimensionless value at xi = x / L and Fourier number fo = D t / L^2.
  double theta(double xi, double fo) const {
    double sum = 0.0;
    for (std::size_t n = 0; n < m_beta.size(); ++n) {
      sum += m_coef[n] * std::cos(m_beta[n] * xi) * std::exp(-m_beta[n] * m_beta[n] * fo);
    }
    return sum;
  }

 private:
  std::vector<double> m_beta, m_coef;
};

/// Slab [0, L] x [0, w] x [0, w] (mm) of nx x 1 x 1 Kuhn cubes, Robin faces on x = L only.
struct SlabProblem {
  TetMesh mesh;
  std::vector<RobinFace> faces;
};

inline SlabProblem make_slab(int nx, double length_mm, double width_mm, double h_m_per_s, double ambient) {
  SlabProblem p;
  p.mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(length_mm, width_mm, width_mm), nx, 1, 1);
  for (const TetFace& f : tet_boundary_faces(p.mesh)) {
    bool on_end = true;
    for (Index v : f.vertices)
      on_end = on_end && std::abs(p.mesh.positions[static_cast<std::size_t>(v)].x() - length_mm) < 1e-9;
    if (on_end) p.faces.push_back(RobinFace{f.vertices, f.tet, h_m_per_s, ambient, 1.0});
  }
  return p;
}

/// Runs the slab (u_0 = 1, u_a = 0, D in m^2/s, Bi) to t_end with `steps` steps; returns the largest nodal
/// error against the series.
inline double slab_error(int nx, int steps, double biot, double fourier_end, bool lumped) {
  const double length = 10.0;  // mm
  const double d_m2 = 1e-9;    // m^2/s
  const double d_mm2 = d_m2 * 1e6;
  const double h_m = biot * d_mm2 / length * 1e-3;  // m/s
  const double t_end = fourier_end * length * length / d_mm2;
  SlabProblem p = make_slab(nx, length, length / nx, h_m, 0.0);  // cubic cells
  DiffusionSettings settings;
  settings.lumped_mass = lumped;
  DiffusionSolver solver(p.mesh, {}, p.faces, settings);
  solver.set_tet_diffusivity(std::vector<double>(p.mesh.tet_count(), d_m2));
  std::vector<double> u(p.mesh.vertex_count(), 1.0);
  for (int s = 0; s < steps; ++s) solver.step(u, t_end / steps);
  const SlabSeries series(biot, 200);
  double error = 0.0;
  for (std::size_t n = 0; n < u.size(); ++n) {
    error = std::max(error, std::abs(u[n] - series.theta(p.mesh.positions[n].x() / length, fourier_end)));
  }
  return error;
}

}  // namespace forensim::test
