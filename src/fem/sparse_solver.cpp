// GCC 12 reports a false -Wnull-dereference inside Eigen's sparse Ref after inlining (the outer index array
// of a SparseMatrix is always allocated).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include "fem/sparse_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>

#include "core/error.hpp"

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
      return std::make_unique<CgSolver<Eigen::DiagonalPreconditioner<double>>>(kind, relative_tolerance,
                                                                               max_iterations);
  }
  throw NumericError("make_sparse_solver: unknown solver kind");
}

}  // namespace forensim
