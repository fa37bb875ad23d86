// Convergence of the P1 / implicit Euler moisture solver against series solutions: a 1D slab with a Robin
// end (insulated sides) and a sphere with a Robin surface. Expected orders: 2 in space (P1 nodal error,
// with dt ~ h^2), 1 in time (implicit Euler).

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "analytic_slab.hpp"
#include "fem/diffusion_solver.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_boundary.hpp"

using namespace forensim;

namespace {

double order(double coarse_error, double fine_error, double refinement) {
  return std::log(coarse_error / fine_error) / std::log(refinement);
}

/// Series solution in a sphere of radius R with -D du/dr = h (u - u_a) at r = R, uniform start:
/// theta = sum C_n exp(-beta_n^2 Fo) sin(beta_n r/R) / (beta_n r/R), 1 - beta cot beta = Bi,
/// C_n = 4 (sin beta - beta cos beta) / (2 beta - sin 2 beta).
class SphereSeries {
 public:
  SphereSeries(double biot, int terms) {
    for (int n = 0; n < terms; ++n) {
      // 1 - b cot b increases from 0 (b -> 0) or -inf (b -> n pi+) to +inf (b -> (n+1) pi-).
      double lo = n * std::numbers::pi + 1e-12;
      double hi = (n + 1) * std::numbers::pi - 1e-12;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (1.0 - mid / std::tan(mid) < biot ? lo : hi) = mid;
      }
      const double b = 0.5 * (lo + hi);
      m_beta.push_back(b);
      m_coef.push_back(4.0 * (std::sin(b) - b * std::cos(b)) / (2.0 * b - std::sin(2.0 * b)));
    }
  }
  double theta(double rho, double fo) const {
    double sum = 0.0;
    for (std::size_t n = 0; n < m_beta.size(); ++n) {
      const double x = m_beta[n] * rho;
      const double shape = x < 1e-8 ? 1.0 : std::sin(x) / x;
      sum += m_coef[n] * shape * std::exp(-m_beta[n] * m_beta[n] * fo);
    }
    return sum;
  }

 private:
  std::vector<double> m_beta, m_coef;
};

/// Ball of radius r (mm): a Kuhn box mesh of [-1, 1]^3 pushed radially onto the ball (x |x|_inf / |x|_2).
TetMesh make_ball(int n, double radius) {
  TetMesh mesh = make_box_tet_mesh(Vec3::Constant(-1.0), Vec3::Constant(1.0), n, n, n);
  for (Vec3& p : mesh.positions) {
    const double norm = p.norm();
    if (norm > 0.0) p *= radius * p.cwiseAbs().maxCoeff() / norm;
  }
  return mesh;
}

double sphere_error(int n, int steps) {
  const double radius = 5.0;  // mm
  const double d_m2 = 1e-9;
  const double d_mm2 = d_m2 * 1e6;
  const double biot = 1.0;
  const double h_m = biot * d_mm2 / radius * 1e-3;
  const double fourier_end = 0.05;
  const double t_end = fourier_end * radius * radius / d_mm2;
  const TetMesh mesh = make_ball(n, radius);
  DiffusionSolver solver(mesh, {}, skin_robin_faces(mesh, {}, h_m, 0.0));
  solver.set_tet_diffusivity(std::vector<double>(mesh.tet_count(), d_m2));
  std::vector<double> u(mesh.vertex_count(), 1.0);
  for (int s = 0; s < steps; ++s) solver.step(u, t_end / steps);
  const SphereSeries series(biot, 200);
  double error = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double rho = std::min(1.0, mesh.positions[i].norm() / radius);
    error = std::max(error, std::abs(u[i] - series.theta(rho, fourier_end)));
  }
  return error;
}

}  // namespace

TEST(DiffusionConvergence, SlabSecondOrderInSpace) {
  // dt ~ h^2 so that the time error shrinks with the space error.
  std::vector<double> errors;
  for (int nx : {10, 20, 40, 80}) {
    errors.push_back(test::slab_error(nx, 3 * nx * nx, 2.0, 0.1, true));
    std::cout << "slab nx " << nx << " steps " << 3 * nx * nx << " max error " << errors.back() << "\n";
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double p = order(errors[i - 1], errors[i], 2.0);
    std::cout << "  observed order " << p << "\n";
    EXPECT_GT(p, 1.8);
  }
}

TEST(DiffusionConvergence, SlabFirstOrderInTime) {
  std::vector<double> errors;
  for (int steps : {5, 10, 20, 40}) {
    errors.push_back(test::slab_error(200, steps, 2.0, 0.1, true));
    std::cout << "slab steps " << steps << " max error " << errors.back() << "\n";
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double p = order(errors[i - 1], errors[i], 2.0);
    std::cout << "  observed order " << p << "\n";
    EXPECT_GT(p, 0.85);
    EXPECT_LT(p, 1.2);
  }
}

TEST(DiffusionConvergence, ConsistentMassConvergesToo) {
  const double coarse = test::slab_error(20, 1200, 2.0, 0.1, false);
  const double fine = test::slab_error(40, 4800, 2.0, 0.1, false);
  std::cout << "consistent mass: " << coarse << " -> " << fine << "\n";
  EXPECT_GT(order(coarse, fine, 2.0), 1.8);
}

TEST(DiffusionConvergence, SphereConverges) {
  std::vector<double> errors;
  for (int n : {4, 8, 16}) {
    errors.push_back(sphere_error(n, 4 * n * n));
    std::cout << "sphere n " << n << " max error " << errors.back() << "\n";
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double p = order(errors[i - 1], errors[i], 2.0);
    std::cout << "  observed order " << p << "\n";
    EXPECT_GT(p, 1.4);  // ~1.6: max norm on a squashed-cube ball whose faceted surface and skewed edge tets add error
  }
}
