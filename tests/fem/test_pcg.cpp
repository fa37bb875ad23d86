#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>

#include "core/parallel.hpp"
#include "fem/pcg.hpp"
#include "fem/tet_element.hpp"
#include "geometry/primitives.hpp"
#include "heat_matrix.hpp"

using namespace forensim;

namespace {

/// Consistent mass + scale * Laplacian on a box (SPD), full symmetric storage.
SparseMatrix heat_matrix(double scale, int cells = 6) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(4, 3, 2), 2 * cells, 3 * cells / 2, cells);
  const SparsityPattern pattern(mesh.tets, mesh.vertex_count(), 1);
  return test::heat_matrix(mesh, pattern, scale);
}

Eigen::VectorXd solve_jacobi(const SparseMatrix& a, const Eigen::VectorXd& b, double tolerance, int* iterations) {
  const Eigen::VectorXd inverse_diagonal = a.diagonal().cwiseInverse();
  Eigen::VectorXd x;
  const double limit = tolerance * b.norm();
  const PcgResult result = preconditioned_cg(
      [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { symmetric_multiply(a, in, out); },
      [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = inverse_diagonal.cwiseProduct(in); }, b, x,
      [&](const Eigen::VectorXd& r, int) { return r.norm() <= limit; }, 1000);
  EXPECT_TRUE(result.converged);
  if (iterations != nullptr) *iterations = result.iterations;
  return x;
}

}  // namespace

TEST(Pcg, SymmetricMultiplyMatchesEigen) {
  const SparseMatrix a = heat_matrix(0.3);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 3.0).array().sin();
  Eigen::VectorXd y;
  symmetric_multiply(a, x, y);
  EXPECT_LT((y - a * x).norm(), 1e-13 * (a * x).norm());
  EXPECT_NEAR(parallel_dot(x, y), x.dot(y), 1e-12 * std::abs(x.dot(y)));
}

TEST(Pcg, ConvergesToTheDirectSolutionAndAWarmStartHelps) {
  const SparseMatrix a = heat_matrix(2.0);
  const Eigen::VectorXd expected = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0).array().cos();
  const Eigen::VectorXd b = a * expected;
  int cold = 0, warm = 0;
  const Eigen::VectorXd x = solve_jacobi(a, b, 1e-12, &cold);
  EXPECT_LT((x - expected).norm(), 1e-9 * expected.norm());
  // An exact preconditioner converges in one iteration.
  Eigen::SimplicialLLT<SparseMatrix> llt(a);
  Eigen::VectorXd y;
  const PcgResult exact =
      preconditioned_cg([&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { symmetric_multiply(a, in, out); },
                        [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = llt.solve(in); }, b, y,
                        [&](const Eigen::VectorXd& r, int) { return r.norm() <= 1e-10 * b.norm(); }, 10);
  EXPECT_TRUE(exact.converged);
  EXPECT_LE(exact.iterations, 2);
  // From a nearby guess (the previous time step) fewer iterations reach the same absolute residual.
  Eigen::VectorXd guess = expected + 1e-4 * Eigen::VectorXd::LinSpaced(a.rows(), 0.0, 1.0);
  const double limit = 1e-12 * b.norm();
  const PcgResult r = preconditioned_cg(
      [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { symmetric_multiply(a, in, out); },
      [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = a.diagonal().cwiseInverse().cwiseProduct(in); }, b,
      guess, [&](const Eigen::VectorXd& res, int) { return res.norm() <= limit; }, 1000);
  warm = r.iterations;
  EXPECT_TRUE(r.converged);
  EXPECT_LT(warm, cold);
  EXPECT_LT((guess - expected).norm(), 1e-9 * expected.norm());
}

TEST(Pcg, SameIteratesAtOneAndTwoThreads) {
  const SparseMatrix a = heat_matrix(5.0, 14);  // 29 x 22 x 15 nodes: several reduction blocks
  ASSERT_GT(a.rows(), 2 * 4096);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), 0.0, 1.0).array().exp();
  set_thread_count(1);
  const Eigen::VectorXd one = solve_jacobi(a, b, 1e-10, nullptr);
  set_thread_count(2);
  const Eigen::VectorXd two = solve_jacobi(a, b, 1e-10, nullptr);
  set_thread_count(0);
  for (Eigen::Index i = 0; i < one.size(); ++i) ASSERT_EQ(one[i], two[i]);
}
