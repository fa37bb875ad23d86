#pragma once
/// Preconditioned conjugate gradients on linear operators (Saad 2003, "Iterative methods for sparse linear
/// systems", algorithm 9.1), with parallel vector operations whose reductions are deterministic (fixed
/// blocks summed in order): the iterates are bitwise identical at any thread count.
///
/// The matrix and the preconditioner are functions, so one loop serves an assembled sparse matrix with a
/// diagonal preconditioner (the moisture step), a matrix-free element operator preconditioned by a sparse
/// Cholesky factor (the corotational solid) and anything in between. The caller decides when to stop: a
/// test on the true residual r = b - A x after every iteration (in the units that matter to the caller,
/// e.g. moisture per node or mm of displacement), not a fixed relative residual.

#include <Eigen/Core>
#include <functional>

#include "fem/sparse_assembly.hpp"

namespace forensim {

/// out = Op(in); `out` has the size of `in` on return (resized if needed). Called from one thread; it may
/// run parallel loops itself.
using LinearOperator = std::function<void(const Eigen::VectorXd& in, Eigen::VectorXd& out)>;

/// Stopping test: true when `residual` (= b - A x at the current iterate) is small enough. `iteration` is
/// the number of iterations done (0: the initial guess).
using PcgConverged = std::function<bool(const Eigen::VectorXd& residual, int iteration)>;

struct PcgResult {
  int iterations = 0;      ///< iterations done
  bool converged = false;  ///< the stopping test accepted the last residual
};

/// Solves A x = b for symmetric positive (semi-)definite A with the symmetric positive definite
/// preconditioner `preconditioner` (an approximation of A^-1). `x` holds the initial guess on entry (zero
/// if its size is wrong) and the last iterate on return. Stops when `converged` accepts the residual or
/// after `max_iterations`. The residual is updated recursively (r -= alpha A p), as usual.
PcgResult preconditioned_cg(const LinearOperator& a, const LinearOperator& preconditioner, const Eigen::VectorXd& b,
                            Eigen::VectorXd& x, const PcgConverged& converged, int max_iterations);

/// Deterministic parallel dot product a . b (same size).
double parallel_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

/// y = A x for a compressed matrix `a` holding a symmetric matrix in full storage (both triangles, e.g. from
/// SparsityPattern): column j is row j, so rows are computed in parallel, each in storage order.
void symmetric_multiply(const SparseMatrix& a, const Eigen::VectorXd& x, Eigen::VectorXd& y);

}  // namespace forensim
