#include "craniofacial/rbf_warp.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {
namespace {

bool finite(const Vec3& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

void check_finite(const std::vector<Vec3>& points, const std::string& what, const char* role) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i]))
      throw InputError(what, std::string(role) + " " + std::to_string(i),
                       "coordinates must be finite (NaN or infinity found)");
  }
}

}  // namespace

RbfWarp::RbfWarp(const std::vector<Vec3>& sources, const std::vector<Vec3>& targets, const std::string& what)
    : m_sources(sources), m_targets(targets) {
  const std::size_t n = sources.size();
  require_input(targets.size() == n, what, "",
                std::to_string(n) + " sources but " + std::to_string(targets.size()) + " targets");
  require_input(
      n >= 4, what, "",
      "needs at least 4 landmark pairs not in one plane (the affine part of eq. 1), got " + std::to_string(n));
  check_finite(sources, what, "source");
  check_finite(targets, what, "target");

  Vec3 lo = sources[0], hi = sources[0];
  for (const Vec3& p : sources) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = (hi - lo).norm();
  require_input(diagonal > 0.0, what, "", "all sources coincide");
  m_centre = 0.5 * (lo + hi);
  m_scale = 0.5 * diagonal;
  m_normalised.resize(n);
  for (std::size_t i = 0; i < n; ++i) m_normalised[i] = (sources[i] - m_centre) / m_scale;

  // Coincident sources make two equal rows (a singular system): name them.
  const double min_separation = 1e-9 * 2.0;  // in normalised units: 1e-9 of the diagonal
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      require_input((m_normalised[i] - m_normalised[j]).norm() > min_separation, what,
                    "sources " + std::to_string(i) + " and " + std::to_string(j),
                    "coincide (closer than 1e-9 of the landmark set's size)");
    }
  }
  // The side conditions need [p_i 1] of full column rank: sources not all in one plane.
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : m_normalised) mean += p;
  mean /= static_cast<double>(n);
  Mat3 covariance = Mat3::Zero();
  for (const Vec3& p : m_normalised) covariance += (p - mean) * (p - mean).transpose();
  covariance /= static_cast<double>(n);
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(covariance);
  const Vec3 spread = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  require_input(spread(0) > 1e-6 * spread(2), what, "",
                "the sources lie in one plane or on one line (extent " + std::to_string(spread(0) * m_scale) +
                    " mm across the best-fit plane): eq. 1's affine part is undetermined; add landmarks off the "
                    "plane");

  const auto size = static_cast<Eigen::Index>(n + 4);
  m_matrix = Eigen::MatrixXd::Zero(size, size);
  for (std::size_t i = 0; i < n; ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    for (std::size_t j = 0; j < n; ++j) {
      m_matrix(ii, static_cast<Eigen::Index>(j)) = rbf_biharmonic((m_normalised[i] - m_normalised[j]).norm());
    }
    for (int k = 0; k < 3; ++k) {
      m_matrix(ii, static_cast<Eigen::Index>(n) + k) = m_normalised[i](k);
      m_matrix(static_cast<Eigen::Index>(n) + k, ii) = m_normalised[i](k);
    }
    m_matrix(ii, static_cast<Eigen::Index>(n) + 3) = 1.0;
    m_matrix(static_cast<Eigen::Index>(n) + 3, ii) = 1.0;
  }
  m_lu.compute(m_matrix);
  if (!m_lu.isInvertible()) {
    throw NumericError(what + ": the RBF system (eq. 1) is singular (rank " + std::to_string(m_lu.rank()) + " of " +
                       std::to_string(size) + ")");
  }
  // Cardinal coefficients A^-1 [I_n; 0], refined once.
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(size, static_cast<Eigen::Index>(n));
  unit.topRows(static_cast<Eigen::Index>(n)).setIdentity();
  m_cardinal = m_lu.solve(unit);
  m_cardinal += m_lu.solve(unit - m_matrix * m_cardinal);
  solve();
}

void RbfWarp::solve() {
  const auto n = static_cast<Eigen::Index>(m_sources.size());
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(n + 4, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    rhs.row(i) = ((m_targets[static_cast<std::size_t>(i)] - m_centre) / m_scale).transpose();
  }
  m_coefficients = m_lu.solve(rhs);
  m_coefficients += m_lu.solve(rhs - m_matrix * m_coefficients);
}

void RbfWarp::set_targets(const std::vector<Vec3>& targets) {
  require_input(targets.size() == m_sources.size(), "RBF warp targets", "",
                "expected " + std::to_string(m_sources.size()) + ", got " + std::to_string(targets.size()));
  check_finite(targets, "RBF warp targets", "target");
  m_targets = targets;
  solve();
}

void RbfWarp::set_target(std::size_t i, const Vec3& target) {
  require_input(i < m_sources.size(), "RBF warp target", std::to_string(i), "index out of range");
  require_input(finite(target), "RBF warp target", std::to_string(i), "coordinates must be finite");
  const Vec3 delta = (target - m_targets[i]) / m_scale;
  m_coefficients += m_cardinal.col(static_cast<Eigen::Index>(i)) * delta.transpose();
  m_targets[i] = target;
}

void RbfWarp::kernel_row(const Vec3& x, double* row) const {
  const std::size_t n = m_normalised.size();
  for (std::size_t j = 0; j < n; ++j) row[j] = rbf_biharmonic((x - m_normalised[j]).norm());
  row[n] = x.x();
  row[n + 1] = x.y();
  row[n + 2] = x.z();
  row[n + 3] = 1.0;
}

Vec3 RbfWarp::evaluate(const Vec3& p) const {
  const Vec3 x = (p - m_centre) / m_scale;
  const std::size_t n = m_normalised.size();
  Vec3 sum = Vec3::Zero();
  for (std::size_t j = 0; j < n; ++j) {
    sum += rbf_biharmonic((x - m_normalised[j]).norm()) * m_coefficients.row(static_cast<Eigen::Index>(j)).transpose();
  }
  const auto a = static_cast<Eigen::Index>(n);
  sum += m_coefficients.middleRows(a, 3).transpose() * x + m_coefficients.row(a + 3).transpose();
  return m_centre + m_scale * sum;
}

std::vector<Vec3> RbfWarp::evaluate_batch(const std::vector<Vec3>& points) const {
  std::vector<Vec3> out(points.size());
  parallel_for(
      0, points.size(), [&](std::size_t i) { out[i] = evaluate(points[i]); }, 512);
  return out;
}

Eigen::MatrixX3d RbfWarp::radial_weights() const {
  // In normalised coordinates f_hat(x) = sum c_hat_j |x - x_j| + ...; with x = (p - centre) / s and
  // f = centre + s f_hat, c_j = c_hat_j (|x - x_j| = |p - p_j| / s, times s).
  return m_coefficients.topRows(static_cast<Eigen::Index>(m_sources.size()));
}

Mat3 RbfWarp::linear_part() const {
  return m_coefficients.middleRows(static_cast<Eigen::Index>(m_sources.size()), 3).transpose();
}

Vec3 RbfWarp::translation() const {
  // f(p) = centre + s (R_hat (p - centre) / s + t_hat) + radial = R p + (centre - R centre + s t_hat) + radial.
  const Mat3 r = linear_part();
  const Vec3 t_hat = m_coefficients.row(static_cast<Eigen::Index>(m_sources.size()) + 3).transpose();
  return m_centre - r * m_centre + m_scale * t_hat;
}

double RbfWarp::max_landmark_residual() const {
  double worst = 0.0;
  for (std::size_t i = 0; i < m_sources.size(); ++i)
    worst = std::max(worst, (evaluate(m_sources[i]) - m_targets[i]).norm());
  return worst;
}

RbfPointWarp::RbfPointWarp(const RbfWarp& warp, const std::vector<Vec3>& points) {
  const std::size_t n = warp.landmark_count();
  m_cardinal_values.resize(static_cast<Eigen::Index>(points.size()), static_cast<Eigen::Index>(n));
  const Eigen::MatrixXd& cardinal = warp.cardinal_coefficients();
  for (std::size_t v = 0; v < points.size(); ++v) {
    require_input(std::isfinite(points[v].x()) && std::isfinite(points[v].y()) && std::isfinite(points[v].z()),
                  "RBF warp points", "point " + std::to_string(v), "coordinates must be finite");
  }
  constexpr std::size_t block = 256;
  parallel_for_chunks(
      0, points.size(),
      [&](std::size_t begin, std::size_t end) {
        const auto rows = static_cast<Eigen::Index>(end - begin);
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> kernel(rows,
                                                                                      static_cast<Eigen::Index>(n + 4));
        for (std::size_t v = begin; v < end; ++v) {
          warp.kernel_row((points[v] - warp.centre()) / warp.scale(),
                          kernel.row(static_cast<Eigen::Index>(v - begin)).data());
        }
        m_cardinal_values.middleRows(static_cast<Eigen::Index>(begin), rows).noalias() = kernel * cardinal;
      },
      block);
}

std::vector<Vec3> RbfPointWarp::warp(const std::vector<Vec3>& targets) const {
  require_input(targets.size() == landmark_count(), "RBF warp targets", "",
                "expected " + std::to_string(landmark_count()) + ", got " + std::to_string(targets.size()));
  Eigen::MatrixX3d q(static_cast<Eigen::Index>(targets.size()), 3);
  for (std::size_t j = 0; j < targets.size(); ++j) {
    require_input(std::isfinite(targets[j].sum()), "RBF warp targets", "target " + std::to_string(j),
                  "coordinates must be finite");
    q.row(static_cast<Eigen::Index>(j)) = targets[j].transpose();
  }
  std::vector<Vec3> out(point_count());
  parallel_for_chunks(
      0, out.size(),
      [&](std::size_t begin, std::size_t end) {
        const auto rows = static_cast<Eigen::Index>(end - begin);
        const Eigen::MatrixX3d block = m_cardinal_values.middleRows(static_cast<Eigen::Index>(begin), rows) * q;
        for (std::size_t v = begin; v < end; ++v) out[v] = block.row(static_cast<Eigen::Index>(v - begin)).transpose();
      },
      1024);
  return out;
}

void RbfPointWarp::move_target(std::size_t j, const Vec3& delta_mm, std::vector<Vec3>& warped) const {
  require_input(j < landmark_count(), "RBF warp target", std::to_string(j), "index out of range");
  require_input(warped.size() == point_count(), "warped points", "",
                "expected " + std::to_string(point_count()) + ", got " + std::to_string(warped.size()));
  const auto col = static_cast<Eigen::Index>(j);
  parallel_for_chunks(
      0, warped.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
          warped[v] += m_cardinal_values(static_cast<Eigen::Index>(v), col) * delta_mm;
      },
      4096);
}

std::vector<Vec3> rbf_warp(const std::vector<Vec3>& sources, const std::vector<Vec3>& targets,
                           const std::vector<Vec3>& points) {
  return RbfWarp(sources, targets).evaluate_batch(points);
}

}  // namespace forensim
