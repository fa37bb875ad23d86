// GCC 12 reports a false -Wnull-dereference inside Eigen's sparse Ref after inlining (the outer index array
// of a SparseMatrix is always allocated).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include "fem/sparse_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fem/pcg.hpp"

// OpenBLAS (the BLAS under CHOLMOD's supernodal factor) splits its kernels over its own threads, by default as
// many as the machine has cores, and the rounding of a factor changes with that count. Declared here rather than
// taken from <cblas.h>: the cblas.h on the include path is whichever BLAS the system's alternatives select, and
// only OpenBLAS's declares it (forensim links OpenBLAS itself).
extern "C" void openblas_set_num_threads(int threads);

namespace forensim {
namespace {

/// BLAS in the calling thread only, set once before the first CHOLMOD factor: a factor is then the same at any
/// core count (forensim's own parallel loops share the cores instead). Measured on the headsq CT body model's
/// 60-day mummify: volume 85.9471 % with OpenBLAS on 2 threads, 85.9528 % on 1, now 85.9528 % either way; its
/// deformation step (55k dofs, 9 factor solves) 0.64 -> 0.69 s on two cores.
void single_threaded_blas() {
  static const bool set = (openblas_set_num_threads(1), true);
  (void)set;
}

}  // namespace

std::string sparse_solver_name(SparseSolverKind kind) {
  switch (kind) {
    case SparseSolverKind::cholmod:
      return "cholmod";
    case SparseSolverKind::cg_incomplete_cholesky:
      return "cg_ic";
    case SparseSolverKind::cg_jacobi:
      return "cg_jacobi";
    case SparseSolverKind::cholmod_single:
      return "cholmod_single";
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

/// CHOLMOD's supernodal factor of P A P^T copied to single precision (structure kept, the double factor
/// freed), with forensim's own supernodal forward and back substitutions in double. Own code because
/// CHOLMOD 3 has no single-precision factors; the substitutions stream L once each, so a float L halves the
/// memory traffic of a solve (the cost of a solve on a 3D factor that does not fit in cache).
class CholmodSingleSolver final : public SparseSpdSolver {
 public:
  void analyse(const SparseMatrix& pattern) override {
    m_llt = std::make_unique<Factor>();
    m_llt->analyzePattern(pattern);
    if (m_llt->info() != Eigen::Success) throw NumericError("CHOLMOD: symbolic analysis failed");
  }
  void factor(const SparseMatrix& matrix) override {
    if (!m_llt) analyse(matrix);
    m_llt->factorize(matrix);
    if (m_llt->info() != Eigen::Success) throw NumericError("CHOLMOD: matrix is not positive definite");
    const cholmod_factor* l = m_llt->factor();
    if (l == nullptr || l->is_super == 0 || l->is_ll == 0 || l->xtype != CHOLMOD_REAL)
      throw NumericError("CHOLMOD: expected a real supernodal LL^T factor");
    const auto n = static_cast<std::size_t>(l->n);
    const auto nsuper = static_cast<std::size_t>(l->nsuper);
    const auto* perm = static_cast<const int*>(l->Perm);
    const auto* super = static_cast<const int*>(l->super);
    const auto* pi = static_cast<const int*>(l->pi);
    const auto* px = static_cast<const int*>(l->px);
    const auto* rows = static_cast<const int*>(l->s);
    const auto* x = static_cast<const double*>(l->x);
    m_perm.assign(perm, perm + n);
    m_super.assign(super, super + nsuper + 1);
    m_pi.assign(pi, pi + nsuper + 1);
    m_px.assign(px, px + nsuper + 1);
    m_rows.assign(rows, rows + m_pi[nsuper]);
    m_values.resize(static_cast<std::size_t>(m_px[nsuper]));
    for (std::size_t k = 0; k < m_values.size(); ++k) m_values[k] = static_cast<float>(x[k]);
    split_tree();
    m_llt.reset();  // the double factor is no longer needed (a refactorisation analyses again)
  }
  void solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override {
    const std::size_t n = m_perm.size();
    if (static_cast<std::size_t>(rhs.size()) != n)
      throw NumericError("CHOLMOD single: right-hand side has the wrong size");
    m_work.resize(n);
    double* y = m_work.data();
    for (std::size_t i = 0; i < n; ++i) y[i] = rhs[m_perm[i]];
    // L y' = y: the two bins of subtrees each on a copy of y whose top rows start at zero (they gather that
    // bin's updates), then the top supernodes on the sums. The same arithmetic at any thread count.
    for (auto& b : m_bin_work) {
      b.assign(y, y + n);
      for (int k : m_top_columns) b[static_cast<std::size_t>(k)] = 0.0;
    }
    parallel_for(
        0, m_bins.size(),
        [&](std::size_t b) {
          for (int sn : m_bins[b]) forward(static_cast<std::size_t>(sn), m_bin_work[b].data(), m_below[b]);
        },
        1);
    for (std::size_t b = 0; b < m_bins.size(); ++b) {
      const double* yb = m_bin_work[b].data();
      for (int k : m_bin_columns[b]) y[k] = yb[k];
    }
    for (int k : m_top_columns) {
      double sum = y[k];
      for (const auto& b : m_bin_work) sum += b[static_cast<std::size_t>(k)];
      y[k] = sum;
    }
    for (int sn : m_top) forward(static_cast<std::size_t>(sn), y, m_below[0]);
    // L^T y'' = y': the top supernodes in reverse, then the bins (each writes its own columns only).
    for (auto it = m_top.rbegin(); it != m_top.rend(); ++it) backward(static_cast<std::size_t>(*it), y, m_below[0]);
    parallel_for(
        0, m_bins.size(),
        [&](std::size_t b) {
          for (auto it = m_bins[b].rbegin(); it != m_bins[b].rend(); ++it)
            backward(static_cast<std::size_t>(*it), y, m_below[b]);
        },
        1);
    if (static_cast<std::size_t>(x.size()) != n) x.resize(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) x[m_perm[i]] = y[i];
  }
  SparseSolverKind kind() const override { return SparseSolverKind::cholmod_single; }

 private:
  /// Eigen's wrapper with access to its CHOLMOD factor.
  struct Factor : Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
    const cholmod_factor* factor() const { return m_cholmodFactor; }
  };
  /// Supernode s of L y = y: its triangle on its own columns, then the rows below it, gathered in `below`
  /// (one contiguous multiply-add per column) and subtracted from y once.
  void forward(std::size_t s, double* y, std::vector<double>& below) const {
    const int k1 = m_super[s];
    const int ncol = m_super[s + 1] - k1;
    const int nrow = m_pi[s + 1] - m_pi[s];
    const int* r = m_rows.data() + m_pi[s];
    const float* ls = m_values.data() + m_px[s];
    for (int j = 0; j < ncol; ++j) {
      const float* col = ls + static_cast<std::ptrdiff_t>(j) * nrow;
      const double v = y[k1 + j] / static_cast<double>(col[j]);
      y[k1 + j] = v;
      for (int i = j + 1; i < ncol; ++i) y[k1 + i] -= static_cast<double>(col[i]) * v;
    }
    const int nb = nrow - ncol;
    if (nb == 0) return;
    below.assign(static_cast<std::size_t>(nb), 0.0);
    double* t = below.data();
    for (int j = 0; j < ncol; ++j) {
      const float* col = ls + static_cast<std::ptrdiff_t>(j) * nrow + ncol;
      const double v = y[k1 + j];
      for (int i = 0; i < nb; ++i) t[i] += static_cast<double>(col[i]) * v;
    }
    for (int i = 0; i < nb; ++i) y[r[ncol + i]] -= t[i];
  }
  /// Supernode s of L^T y = y: the solved rows below it gathered once, then per column (in reverse) one
  /// contiguous dot product with them and the triangle's part.
  void backward(std::size_t s, double* y, std::vector<double>& below) const {
    const int k1 = m_super[s];
    const int ncol = m_super[s + 1] - k1;
    const int nrow = m_pi[s + 1] - m_pi[s];
    const int* r = m_rows.data() + m_pi[s];
    const float* ls = m_values.data() + m_px[s];
    const int nb = nrow - ncol;
    below.resize(static_cast<std::size_t>(nb));
    double* t = below.data();
    for (int i = 0; i < nb; ++i) t[i] = y[r[ncol + i]];
    for (int j = ncol - 1; j >= 0; --j) {
      const float* col = ls + static_cast<std::ptrdiff_t>(j) * nrow;
      const float* tail = col + ncol;
      double acc0 = 0.0, acc1 = 0.0, acc2 = 0.0, acc3 = 0.0;
      int i = 0;
      for (; i + 3 < nb; i += 4) {
        acc0 += static_cast<double>(tail[i]) * t[i];
        acc1 += static_cast<double>(tail[i + 1]) * t[i + 1];
        acc2 += static_cast<double>(tail[i + 2]) * t[i + 2];
        acc3 += static_cast<double>(tail[i + 3]) * t[i + 3];
      }
      for (; i < nb; ++i) acc0 += static_cast<double>(tail[i]) * t[i];
      for (int k = j + 1; k < ncol; ++k) acc1 += static_cast<double>(col[k]) * y[k1 + k];
      y[k1 + j] = (y[k1 + j] - ((acc0 + acc1) + (acc2 + acc3))) / static_cast<double>(col[j]);
    }
  }

  /// Splits the supernodal elimination tree into a top part (solved alone) and two bins of disjoint
  /// subtrees of about equal work (solved side by side): the heaviest subtree is opened (its root moves to
  /// the top) until the bins balance. Depends on the factor's structure only.
  void split_tree() {
    const std::size_t nsuper = m_super.size() - 1;
    std::vector<int> column_super(static_cast<std::size_t>(m_super[nsuper]));
    for (std::size_t s = 0; s < nsuper; ++s)
      for (int k = m_super[s]; k < m_super[s + 1]; ++k) column_super[static_cast<std::size_t>(k)] = static_cast<int>(s);
    std::vector<int> parent(nsuper, -1);
    std::vector<std::vector<int>> children(nsuper);
    std::vector<double> work(nsuper, 0.0);
    std::vector<int> roots;
    for (std::size_t s = 0; s < nsuper; ++s) {
      const int ncol = m_super[s + 1] - m_super[s];
      const int nrow = m_pi[s + 1] - m_pi[s];
      work[s] += static_cast<double>(m_px[s + 1] - m_px[s]);
      if (nrow > ncol) {
        parent[s] = column_super[static_cast<std::size_t>(m_rows[static_cast<std::size_t>(m_pi[s] + ncol)])];
        children[static_cast<std::size_t>(parent[s])].push_back(static_cast<int>(s));
      } else {
        roots.push_back(static_cast<int>(s));
      }
    }
    std::vector<double> subtree = work;  // children have smaller indices than their parents
    for (std::size_t s = 0; s < nsuper; ++s)
      if (parent[s] >= 0) subtree[static_cast<std::size_t>(parent[s])] += subtree[s];
    std::vector<int> candidates = roots;
    std::vector<std::uint8_t> top(nsuper, 0);
    auto heaviest = [&]() {
      return std::max_element(candidates.begin(), candidates.end(), [&](int a, int b) {
        return subtree[static_cast<std::size_t>(a)] < subtree[static_cast<std::size_t>(b)];
      });
    };
    for (int opened = 0; opened < 256 && !candidates.empty(); ++opened) {
      double total = 0.0;
      for (int c : candidates) total += subtree[static_cast<std::size_t>(c)];
      const auto h = heaviest();
      if (subtree[static_cast<std::size_t>(*h)] <= 0.5 * total) break;
      const int s = *h;
      candidates.erase(h);
      top[static_cast<std::size_t>(s)] = 1;
      for (int c : children[static_cast<std::size_t>(s)]) candidates.push_back(c);
    }
    // Largest first into the lighter bin (ties: bin 0), the candidates sorted for a fixed result.
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
      const double wa = subtree[static_cast<std::size_t>(a)], wb = subtree[static_cast<std::size_t>(b)];
      return wa != wb ? wa > wb : a < b;
    });
    std::vector<int> bin_of(nsuper, -1);
    double load[2] = {0.0, 0.0};
    std::vector<int> stack;
    for (int c : candidates) {
      const int b = load[1] < load[0] ? 1 : 0;
      load[b] += subtree[static_cast<std::size_t>(c)];
      stack.assign(1, c);
      while (!stack.empty()) {
        const int s = stack.back();
        stack.pop_back();
        bin_of[static_cast<std::size_t>(s)] = b;
        for (int ch : children[static_cast<std::size_t>(s)]) stack.push_back(ch);
      }
    }
    m_bins.assign(2, {});
    m_bin_columns.assign(2, {});
    m_top.clear();
    m_top_columns.clear();
    for (std::size_t s = 0; s < nsuper; ++s) {
      const bool in_top = bin_of[s] < 0;
      if (in_top) {
        m_top.push_back(static_cast<int>(s));
      } else {
        m_bins[static_cast<std::size_t>(bin_of[s])].push_back(static_cast<int>(s));
      }
      for (int k = m_super[s]; k < m_super[s + 1]; ++k) {
        if (in_top) {
          m_top_columns.push_back(k);
        } else {
          m_bin_columns[static_cast<std::size_t>(bin_of[s])].push_back(k);
        }
      }
    }
    m_bin_work.assign(2, {});
    m_below.assign(2, {});
  }

  std::unique_ptr<Factor> m_llt;
  std::vector<int> m_perm, m_super, m_pi, m_px, m_rows;
  std::vector<float> m_values;
  std::vector<double> m_work;
  std::vector<std::vector<int>> m_bins, m_bin_columns;  // supernodes (increasing) and their columns per bin
  std::vector<int> m_top, m_top_columns;                // the rest: ancestors of the bins' subtrees
  std::vector<std::vector<double>> m_bin_work;
  mutable std::vector<std::vector<double>> m_below;  // per bin: scratch for the rows below a supernode
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
      single_threaded_blas();
      return std::make_unique<CholmodSolver>();
    case SparseSolverKind::cg_incomplete_cholesky:
      return std::make_unique<CgSolver<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>>(
          kind, relative_tolerance, max_iterations);
    case SparseSolverKind::cg_jacobi:
      return std::make_unique<JacobiCgSolver>(relative_tolerance, max_iterations);
    case SparseSolverKind::cholmod_single:
      single_threaded_blas();
      return std::make_unique<CholmodSingleSolver>();
  }
  throw NumericError("make_sparse_solver: unknown solver kind");
}

}  // namespace forensim
