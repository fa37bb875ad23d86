#include <gtest/gtest.h>
#include <cmath>

#include "core/parallel.hpp"
#include "fem/sparse_solver.hpp"
#include "fem/tet_element.hpp"
#include "geometry/primitives.hpp"
#include "heat_matrix.hpp"

using namespace forensim;

namespace {

using test::heat_matrix;

}  // namespace

class SparseSolverKinds : public ::testing::TestWithParam<SparseSolverKind> {};

TEST_P(SparseSolverKinds, SolvesAndRefactorsWithTheSameAnalysis) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(4, 3, 2), 8, 6, 4);
  const SparsityPattern pattern(mesh.tets, mesh.vertex_count(), 1);
  auto solver = make_sparse_solver(GetParam(), 1e-12);
  EXPECT_EQ(solver->kind(), GetParam());
  solver->analyse(pattern.make_matrix());
  Eigen::VectorXd expected = Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(mesh.vertex_count()), -1.0, 2.0);
  for (double scale : {0.1, 10.0}) {
    const SparseMatrix a = heat_matrix(mesh, pattern, scale);
    solver->factor(a);
    const Eigen::VectorXd b = a * expected;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
    solver->solve(b, x);
    EXPECT_LT((x - expected).norm(), 1e-8 * expected.norm()) << sparse_solver_name(GetParam());
    if (GetParam() != SparseSolverKind::cholmod) {
      // Warm start from the answer: (almost) no iterations.
      const int cold = solver->last_iterations();
      solver->solve(b, x);
      EXPECT_LE(solver->last_iterations(), cold / 2 + 1);
    }
  }
}

TEST_P(SparseSolverKinds, SolvesSeveralColumnsAtOnce) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(4, 3, 2), 6, 5, 4);
  const SparsityPattern pattern(mesh.tets, mesh.vertex_count(), 1);
  const SparseMatrix a = heat_matrix(mesh, pattern, 1.0);
  auto solver = make_sparse_solver(GetParam(), 1e-12);
  solver->analyse(a);
  solver->factor(a);
  const auto n = static_cast<Eigen::Index>(mesh.vertex_count());
  Eigen::MatrixXd expected(n, 3);
  expected.col(0) = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  expected.col(1) = Eigen::VectorXd::Ones(n);
  expected.col(2) = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0).array().square();
  const Eigen::MatrixXd b = a * expected;
  Eigen::MatrixXd x;
  solver->solve_columns(b, x);
  ASSERT_EQ(x.rows(), n);
  ASSERT_EQ(x.cols(), 3);
  for (Eigen::Index c = 0; c < 3; ++c) {
    EXPECT_LT((x.col(c) - expected.col(c)).norm(), 1e-8 * expected.col(c).norm()) << sparse_solver_name(GetParam());
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, SparseSolverKinds,
                         ::testing::Values(SparseSolverKind::cholmod, SparseSolverKind::cg_incomplete_cholesky,
                                           SparseSolverKind::cg_jacobi));

TEST(SparseSolver, CholmodRejectsIndefiniteMatrix) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3::Ones(), 2, 2, 2);
  const SparsityPattern pattern(mesh.tets, mesh.vertex_count(), 1);
  SparseMatrix a = heat_matrix(mesh, pattern, 1.0);
  a = -a;
  auto solver = make_sparse_solver(SparseSolverKind::cholmod);
  solver->analyse(a);
  EXPECT_THROW(solver->factor(a), std::exception);
}

TEST(SparseSolver, SinglePrecisionFactorIsAnAccurateSymmetricInverseAtAnyThreadCount) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(4, 3, 2), 14, 11, 8);
  const SparsityPattern pattern(mesh.tets, mesh.vertex_count(), 1);
  const SparseMatrix a = heat_matrix(mesh, pattern, 1.0);
  auto solver = make_sparse_solver(SparseSolverKind::cholmod_single);
  EXPECT_EQ(solver->kind(), SparseSolverKind::cholmod_single);
  solver->analyse(a);
  solver->factor(a);
  const auto n = static_cast<Eigen::Index>(mesh.vertex_count());
  const Eigen::VectorXd expected = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd b = a * expected;
  Eigen::VectorXd x;
  solver->solve(b, x);
  // Float factor: error of order cond(A) 1e-7, far from the 1e-8 relative of the double factor's test.
  const double error = (x - expected).norm() / expected.norm();
  EXPECT_LT(error, 1e-4);
  EXPECT_GT(error, 1e-13);  // it is the float factor that solved
  // The operator (L~ L~^T)^-1 is symmetric: u . P v = v . P u to double rounding.
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0).array().sin();
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n, 3.0, -1.0).array().cos();
  Eigen::VectorXd pu, pv;
  solver->solve(u, pu);
  solver->solve(v, pv);
  EXPECT_NEAR(u.dot(pv), v.dot(pu), 1e-12 * std::abs(u.dot(pv)));
  EXPECT_GT(u.dot(pu), 0.0);
  // The subtrees solved side by side give the same bits at any thread count.
  set_thread_count(1);
  Eigen::VectorXd serial;
  solver->solve(b, serial);
  set_thread_count(0);
  EXPECT_EQ(serial, x);
}
