#pragma once
/// Sparse symmetric positive-definite solvers behind one interface, with a setup-once, solve-many shape:
/// analyse(pattern) once per sparsity pattern, factor(values) whenever the values change (every time step
/// for coefficient-dependent FEM matrices), solve as often as needed.
///
/// Backends: CHOLMOD supernodal Cholesky (symbolic analysis and fill-reducing ordering kept across
/// refactorisations) and Eigen's conjugate gradient with an incomplete-Cholesky or Jacobi preconditioner,
/// warm-started from the `x` passed to solve. This interface is also where a distributed backend (PETSc
/// KSP/PC, for meshes too large for one machine) would go later: analyse/factor/solve map onto
/// KSPSetOperators/PCSetUp/KSPSolve.

#include <memory>
#include <string>

#include "fem/sparse_assembly.hpp"

namespace forensim {

enum class SparseSolverKind {
  cholmod,                 ///< supernodal Cholesky (CHOLMOD), exact to rounding
  cg_incomplete_cholesky,  ///< preconditioned CG, incomplete Cholesky (AMD-ordered), warm start
  cg_jacobi,               ///< preconditioned CG, diagonal preconditioner, warm start
  /// CHOLMOD's supernodal factor kept in single precision and solved by forensim (substitutions in double
  /// on the float factor L~): the operator (L~ L~^T)^-1 is symmetric positive definite and within about
  /// cond(A) 1e-7 of A^-1, at half the memory (and memory traffic per solve) of the double factor. For
  /// preconditioners, where the solve dominates and a relative error of 1e-7 cond(A) does no harm.
  cholmod_single,
};

/// Name of a solver kind ("cholmod", "cg_ic", "cg_jacobi", "cholmod_single").
std::string sparse_solver_name(SparseSolverKind kind);

class SparseSpdSolver {
 public:
  virtual ~SparseSpdSolver() = default;
  /// Symbolic work for the structure of `pattern` (full symmetric storage, square). Call once per pattern.
  virtual void analyse(const SparseMatrix& pattern) = 0;
  /// Numeric work for `matrix` (same structure as analysed; symmetric positive definite). The solver keeps
  /// what it needs; `matrix` may change afterwards. Throws NumericError if the matrix is not SPD.
  virtual void factor(const SparseMatrix& matrix) = 0;
  /// Solves A x = rhs with the last factored A. `x` holds the initial guess on entry (used by iterative
  /// backends; resized and zeroed if its size is wrong) and the solution on return. Throws NumericError
  /// when an iterative backend does not reach its tolerance.
  virtual void solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) = 0;
  /// Solves A X = B for the columns of `rhs` (#n by #k) with the last factored A; `x` as in solve(), per
  /// column. Direct backends solve all columns in one pass over the factor (cheaper than k solves); the
  /// default solves column by column.
  virtual void solve_columns(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& x);
  /// Iterations of the last solve (0 for direct solvers).
  virtual int last_iterations() const { return 0; }
  virtual SparseSolverKind kind() const = 0;
};

/// Creates a solver. `relative_tolerance` (|r| / |b|) and `max_iterations` apply to the CG backends.
std::unique_ptr<SparseSpdSolver> make_sparse_solver(SparseSolverKind kind, double relative_tolerance = 1e-12,
                                                    int max_iterations = 5000);

}  // namespace forensim
