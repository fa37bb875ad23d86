// GCC 12 reports a false -Wnull-dereference inside Eigen's sparse Ref after inlining (the outer index array
// of a SparseMatrix is always allocated).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include "fem/sparse_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <cmath>

#include "core/error.hpp"
#include "fem/pcg.hpp"

namespace forensim {

std::string sparse_solver_name(SparseSolverKind kind) {
  switch (kind) {
    case SparseSolverKind::cholmod:
      return "cholmod";
    case SparseSolverKind::cg_incomplete_cholesky:
      return "cg_ic";
    case SparseSolverKind::cg_jacobi:
      return "cg_jacobi";
  }
  return "unknown";
}

void SparseSpdSolver::solve_columns(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& x) {
  if (x.rows() != rhs.rows() || x.cols() != rhs.cols()) x = Eigen::MatrixXd::Zero(rhs.rows(), rhs.cols());
  Eigen::VectorXd column;
  for (Eigen::Index c = 0; c < rhs.cols(); ++c) {
    column = x.col(c);
    solve(rhs.col(c), column);
    x.col(c) = column;
  }
}

namespace {

class CholmodSolver final : public SparseSpdSolver {
 public:
  void analyse(const SparseMatrix& pattern) override {
    m_llt.analyzePattern(pattern);
    if (m_llt.info() != Eigen::Success) throw NumericError("CHOLMOD: symbolic analysis failed");
    m_analysed = true;
  }
  void factor(const SparseMatrix& matrix) override {
    if (!m_analysed) analyse(matrix);
    m_llt.factorize(matrix);
    if (m_llt.info() != Eigen::Success) throw NumericError("CHOLMOD: matrix is not positive definite");
  }
  void solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override {
    x = m_llt.solve(rhs);
    if (m_llt.info() != Eigen::Success) throw NumericError("CHOLMOD: solve failed");
  }
  void solve_columns(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& x) override {
    x = m_llt.solve(rhs);
    if (m_llt.info() != Eigen::Success) throw NumericError("CHOLMOD: solve failed");
  }
  SparseSolverKind kind() const override { return SparseSolverKind::cholmod; }

 private:
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> m_llt;
  bool m_analysed = false;
};

template <typename Preconditioner>
class CgSolver final : public SparseSpdSolver {
 public:
  CgSolver(SparseSolverKind kind, double tolerance, int max_iterations) : m_kind(kind) {
    m_cg.setTolerance(tolerance);
    m_cg.setMaxIterations(max_iterations);
  }
  void analyse(const SparseMatrix& pattern) override {
    m_matrix = pattern;
    m_cg.analyzePattern(m_matrix);
    m_analysed = true;
  }
  void factor(const SparseMatrix& matrix) override {
    // Eigen's CG keeps a reference to its matrix: hold a copy so that the caller may reuse theirs.
    m_matrix = matrix;
    if (!m_analysed) {
      m_cg.analyzePattern(m_matrix);
      m_analysed = true;
    }
    m_cg.factorize(m_matrix);
    if (m_cg.info() != Eigen::Success) throw NumericError("CG: preconditioner set-up failed");
  }
  void solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override {
    if (x.size() != rhs.size()) x = Eigen::VectorXd::Zero(rhs.size());
    x = m_cg.solveWithGuess(rhs, x);
    m_iterations = static_cast<int>(m_cg.iterations());
    if (m_cg.info() != Eigen::Success) {
      throw NumericError("CG: no convergence in " + std::to_string(m_iterations) + " iterations (relative residual " +
                         std::to_string(m_cg.error()) + ")");
    }
  }
  int last_iterations() const override { return m_iterations; }
  SparseSolverKind kind() const override { return m_kind; }

 private:
  SparseSolverKind m_kind;
  SparseMatrix m_matrix;
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Preconditioner> m_cg;
  bool m_analysed = false;
  int m_iterations = 0;
};

/// Jacobi-preconditioned CG on forensim's parallel, deterministic PCG (fem/pcg.hpp).
class JacobiCgSolver final : public SparseSpdSolver {
 public:
  JacobiCgSolver(double tolerance, int max_iterations) : m_tolerance(tolerance), m_max_iterations(max_iterations) {}
  void analyse(const SparseMatrix& pattern) override { m_matrix = pattern; }
  void factor(const SparseMatrix& matrix) override {
    m_matrix = matrix;
    m_inverse_diagonal = m_matrix.diagonal();
    for (Eigen::Index i = 0; i < m_inverse_diagonal.size(); ++i) {
      if (!(m_inverse_diagonal[i] > 0.0)) throw NumericError("CG: matrix has a non-positive diagonal entry");
      m_inverse_diagonal[i] = 1.0 / m_inverse_diagonal[i];
    }
  }
  void solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override {
    if (x.size() != rhs.size()) x = Eigen::VectorXd::Zero(rhs.size());
    const double limit = m_tolerance * std::sqrt(parallel_dot(rhs, rhs));
    double last = 0.0;
    const PcgResult result = preconditioned_cg(
        [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { symmetric_multiply(m_matrix, in, out); },
        [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = m_inverse_diagonal.cwiseProduct(in); }, rhs, x,
        [&](const Eigen::VectorXd& r, int) {
          last = std::sqrt(parallel_dot(r, r));
          return last <= limit;
        },
        m_max_iterations);
    m_iterations = result.iterations;
    if (!result.converged) {
      throw NumericError("CG: no convergence in " + std::to_string(m_iterations) + " iterations (residual " +
                         std::to_string(last) + ", wanted " + std::to_string(limit) + ")");
    }
  }
  int last_iterations() const override { return m_iterations; }
  SparseSolverKind kind() const override { return SparseSolverKind::cg_jacobi; }

 private:
  double m_tolerance;
  int m_max_iterations;
  SparseMatrix m_matrix;
  Eigen::VectorXd m_inverse_diagonal;
  int m_iterations = 0;
};

}  // namespace

std::unique_ptr<SparseSpdSolver> make_sparse_solver(SparseSolverKind kind, double relative_tolerance,
                                                    int max_iterations) {
  switch (kind) {
    case SparseSolverKind::cholmod:
      return std::make_unique<CholmodSolver>();
    case SparseSolverKind::cg_incomplete_cholesky:
      return std::make_unique<CgSolver<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>>(
          kind, relative_tolerance, max_iterations);
    case SparseSolverKind::cg_jacobi:
      return std::make_unique<JacobiCgSolver>(relative_tolerance, max_iterations);
  }
  throw NumericError("make_sparse_solver: unknown solver kind");
}

}  // namespace forensim
