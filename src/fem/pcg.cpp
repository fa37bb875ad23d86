#include "fem/pcg.hpp"

#include <cmath>

#include "core/parallel.hpp"

namespace forensim {

namespace {

constexpr std::size_t vector_block = 4096;  // fixed reduction blocks: results independent of the thread count

std::size_t size_of(const Eigen::VectorXd& v) {
  return static_cast<std::size_t>(v.size());
}

}  // namespace

double parallel_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double* pa = a.data();
  const double* pb = b.data();
  return parallel_sum_chunks(
      0, size_of(a),
      [&](std::size_t lo, std::size_t hi) {
        double s = 0.0;
        for (std::size_t i = lo; i < hi; ++i) s += pa[i] * pb[i];
        return s;
      },
      vector_block);
}

void symmetric_multiply(const SparseMatrix& a, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  y.resize(a.rows());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* values = a.valuePtr();
  const double* px = x.data();
  double* py = y.data();
  parallel_for_chunks(
      0, static_cast<std::size_t>(a.cols()),
      [&](std::size_t lo, std::size_t hi) {
        for (std::size_t j = lo; j < hi; ++j) {
          double s = 0.0;
          for (int k = outer[j]; k < outer[j + 1]; ++k) s += values[k] * px[inner[k]];
          py[j] = s;
        }
      },
      1024);
}

PcgResult preconditioned_cg(const LinearOperator& a, const LinearOperator& preconditioner, const Eigen::VectorXd& b,
                            Eigen::VectorXd& x, const PcgConverged& converged, int max_iterations) {
  const std::size_t n = size_of(b);
  if (size_of(x) != n) x = Eigen::VectorXd::Zero(b.size());
  PcgResult result;
  Eigen::VectorXd r, z, p, q;
  if (x.isZero(0.0)) {
    r = b;  // a zero guess needs no product (inexact Newton steps start from zero)
  } else {
    a(x, q);
    r = b - q;
  }
  if (converged(r, 0)) {
    result.converged = true;
    return result;
  }
  preconditioner(r, z);
  p = z;
  double rz = parallel_dot(r, z);
  for (int it = 1; it <= max_iterations; ++it) {
    a(p, q);
    const double pq = parallel_dot(p, q);
    if (!(pq > 0.0) || !std::isfinite(pq)) break;  // breakdown: A not positive definite along p (or r = 0)
    const double alpha = rz / pq;
    double* px = x.data();
    double* pr = r.data();
    const double* pp = p.data();
    const double* pqv = q.data();
    parallel_for_chunks(
        0, n,
        [&](std::size_t lo, std::size_t hi) {
          for (std::size_t i = lo; i < hi; ++i) {
            px[i] += alpha * pp[i];
            pr[i] -= alpha * pqv[i];
          }
        },
        vector_block);
    result.iterations = it;
    if (converged(r, it)) {
      result.converged = true;
      return result;
    }
    preconditioner(r, z);
    const double rz_next = parallel_dot(r, z);
    const double beta = rz_next / rz;
    rz = rz_next;
    double* ppw = p.data();
    const double* pz = z.data();
    parallel_for_chunks(
        0, n,
        [&](std::size_t lo, std::size_t hi) {
          for (std::size_t i = lo; i < hi; ++i) ppw[i] = pz[i] + beta * ppw[i];
        },
        vector_block);
  }
  return result;
}

}  // namespace forensim
