#pragma once
/// Stretch (distance) constraint of position-based dynamics (Mueller, Heidelberger, Hennix and Ratcliff 2007,
/// "Position based dynamics", section 4.2; Frerichs, Vidler and Gatzidis 2020, section 8.1): one per skin edge,
/// C(p0, p1) = |p0 - p1| - d with the edge's rest length d. The kernel is a pure function of two points; the
/// constraint set holds the rest data of every edge of a mesh.

#include <array>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace forensim {

/// Position corrections of a two-particle projection.
struct PairCorrection {
  Vec3 dp0 = Vec3::Zero(), dp1 = Vec3::Zero();
};

/// C = |p0 - p1| - rest_length (mm for positions in mm).
double stretch_value(const Vec3& p0, const Vec3& p1, double rest_length);

/// Projection of the stretch constraint (Mueller et al. 2007, eq. 10 and 11): with n = (p0 - p1) / |p0 - p1|,
/// dp0 = -w0 / (w0 + w1) k C n, dp1 = +w1 / (w0 + w1) k C n. `w0`, `w1` are inverse masses (>= 0), `stiffness`
/// k in [0, 1] (1 satisfies the constraint in one projection). Zero corrections when both particles are fixed
/// or coincide. m0 dp0 + m1 dp1 = 0: the projection conserves linear momentum.
inline PairCorrection project_stretch(const Vec3& p0, const Vec3& p1, double w0, double w1, double rest_length,
                                      double stiffness);

/// Stretch constraints of every unique edge of a triangle mesh (Model data, #E entries each).
struct StretchConstraints {
  std::vector<std::array<Index, 2>> edge_vertices;  ///< #E, smaller vertex index first, sorted
  std::vector<double> edge_rest_length;             ///< #E, d (mm)
  std::size_t size() const { return edge_vertices.size(); }
};

/// One constraint per unique edge of `triangles`, rest lengths from `positions` (#V). Throws InputError naming
/// `source` for an index out of range or a zero-length edge.
StretchConstraints make_stretch_constraints(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles,
                                            const std::string& source);

inline PairCorrection project_stretch(const Vec3& p0, const Vec3& p1, double w0, double w1, double rest_length,
                                      double stiffness) {
  PairCorrection out;
  const double w = w0 + w1;
  const Vec3 d = p0 - p1;
  const double length = d.norm();
  if (w <= 0.0 || length <= 0.0) return out;
  const Vec3 n = d / length;
  const double s = stiffness * (length - rest_length) / w;
  out.dp0 = -w0 * s * n;
  out.dp1 = w1 * s * n;
  return out;
}

}  // namespace forensim
