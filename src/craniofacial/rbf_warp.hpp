#pragma once
/// Landmark-based RBF space warp (Kähler, Haber and Seidel 2003, "Reanimating the dead", section 4.2, eq. 1):
///
///   f(p) = sum_{i=1..n} c_i phi(|p - p_i|) + R p + t,   phi(r) = r (the biharmonic basis in 3D, which
///   minimises bending energy; Duchon 1977),
///
/// with the side conditions sum_i c_i = 0 and sum_i c_i p_i^T = 0 (no affine part in the radial sum), so that
/// f(p_i) = q_i for every landmark pair. The (n + 4) x (n + 4) saddle-point system is solved by LU with full
/// pivoting (Eigen::FullPivLU) in coordinates centred on the sources and scaled to unit size (the same warp,
/// better conditioned), plus one step of iterative refinement. The system matrix depends on the sources only,
/// so new targets cost one O(n^2) back-substitution, and a fixed point set can cache its cardinal functions
/// (RbfPointWarp) so that moving one target moves every point in O(#points).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "core/types.hpp"

namespace forensim {

/// The biharmonic radial basis in 3D, phi(r) = r (eq. 1).
inline double rbf_biharmonic(double r) {
  return r;
}

/// f of eq. 1 for one set of source landmarks. Setup once (factorisation), evaluate many points; the targets
/// can be changed without refactoring. Evaluation is const and thread-safe.
class RbfWarp {
 public:
  /// `sources`: n >= 4 landmark positions p_i (mm), not all in one plane, no two closer than 1e-9 of their
  /// bounding-box diagonal; `targets`: n positions q_i (mm). `what` names the landmark set in errors. Throws
  /// InputError for sizes that differ, fewer than 4 landmarks, non-finite coordinates, coincident sources
  /// (naming both indices) or coplanar/collinear sources, and NumericError if the system is singular anyway.
  RbfWarp(const std::vector<Vec3>& sources, const std::vector<Vec3>& targets,
          const std::string& what = "RBF warp landmarks");

  /// f(p) (eq. 1), mm.
  Vec3 evaluate(const Vec3& p) const;
  Vec3 operator()(const Vec3& p) const { return evaluate(p); }
  /// f at every point, in parallel (result i belongs to points[i]; bitwise the same at any thread count).
  std::vector<Vec3> evaluate_batch(const std::vector<Vec3>& points) const;

  /// New targets (n positions, finite; else InputError): one back-substitution with the stored LU, O(n^2).
  void set_targets(const std::vector<Vec3>& targets);
  /// Moves target i: O(n) with the stored column i of the inverse system (exact up to rounding).
  void set_target(std::size_t i, const Vec3& target);

  std::size_t landmark_count() const { return m_sources.size(); }
  const std::vector<Vec3>& sources() const { return m_sources; }
  const std::vector<Vec3>& targets() const { return m_targets; }
  /// c_i of eq. 1, n x 3 (mm per mm of distance).
  Eigen::MatrixX3d radial_weights() const;
  /// R of eq. 1 (3 x 3) and t (mm), in the caller's coordinates.
  Mat3 linear_part() const;
  Vec3 translation() const;
  /// Largest |f(p_i) - q_i| over the landmarks (mm): the interpolation residual.
  double max_landmark_residual() const;

  /// Row of the kernel for a point in normalised coordinates: [phi(|x - p_j|) for j < n, x, 1], length n + 4.
  /// For RbfPointWarp; `x_normalised` = (p - centre()) / scale().
  void kernel_row(const Vec3& x_normalised, double* row) const;
  const Vec3& centre() const { return m_centre; }
  double scale() const { return m_scale; }
  /// Columns 0..n-1 of the inverse system matrix, (n + 4) x n: the coefficients of each cardinal function.
  const Eigen::MatrixXd& cardinal_coefficients() const { return m_cardinal; }

 private:
  void solve();

  std::vector<Vec3> m_sources, m_targets;
  Vec3 m_centre = Vec3::Zero();
  double m_scale = 1.0;
  std::vector<Vec3> m_normalised;  ///< (p_i - centre) / scale
  Eigen::MatrixXd m_matrix;        ///< the (n + 4) x (n + 4) system in normalised coordinates
  Eigen::FullPivLU<Eigen::MatrixXd> m_lu;
  Eigen::MatrixXd m_cardinal;       ///< A^-1 [I_n; 0], (n + 4) x n
  Eigen::MatrixX3d m_coefficients;  ///< (n + 4) x 3: radial weights (normalised), then the affine rows
};

/// The warp of a fixed set of points (a template head's skin vertices and muscle grids) under RBF warps with
/// fixed sources: stores the cardinal functions L_j(x_v) (eq. 1 is linear in the targets: f(x) = sum_j L_j(x)
/// q_j), #points x n doubles, built in parallel in O(#points n^2). Then all targets cost O(#points n) and
/// moving one target O(#points): the interactive case of moving one landmark.
class RbfPointWarp {
 public:
  /// `warp` gives the sources (its targets are not used); `points` in mm.
  RbfPointWarp(const RbfWarp& warp, const std::vector<Vec3>& points);

  /// f(x_v) for all points, for n targets (InputError for a wrong count). Parallel, deterministic.
  std::vector<Vec3> warp(const std::vector<Vec3>& targets) const;
  /// Adds the effect of target j moving by `delta_mm` to `warped` (#points positions): warped_v +=
  /// L_j(x_v) delta. O(#points).
  void move_target(std::size_t j, const Vec3& delta_mm, std::vector<Vec3>& warped) const;

  std::size_t point_count() const { return static_cast<std::size_t>(m_cardinal_values.rows()); }
  std::size_t landmark_count() const { return static_cast<std::size_t>(m_cardinal_values.cols()); }
  /// L_j(x_v), #points x n.
  const Eigen::MatrixXd& cardinal_values() const { return m_cardinal_values; }

 private:
  Eigen::MatrixXd m_cardinal_values;
};

/// One-call form: f(points) for the warp taking `sources` onto `targets` (same errors as RbfWarp).
std::vector<Vec3> rbf_warp(const std::vector<Vec3>& sources, const std::vector<Vec3>& targets,
                           const std::vector<Vec3>& points);

}  // namespace forensim
