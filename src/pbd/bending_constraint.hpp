#pragma once
/// Bending constraint of position-based dynamics on the dihedral angle of two triangles that share an edge
/// (Mueller et al. 2007, "Position based dynamics", section 4.2 and appendix; Frerichs, Vidler and Gatzidis 2020,
/// section 8.1). Particles: x0 and x1 are the wing vertices, (x2, x3) the shared edge; the triangles are
/// (x0, x2, x3) and (x1, x3, x2), both counter-clockwise from outside. C = theta - theta_0 with theta the signed
/// angle between the two face normals, atan2((nA x nB) . e, nA . nB) in (-pi, pi] (0 for a flat pair). Mueller's
/// acos(nA . nB) is unsigned and its gradient is singular at the flat rest state of a smooth skin; the signed
/// angle with the gradients of Bridson, Marino and Fedkiw 2003 ("Simulation of clothing with folds and
/// wrinkles") is smooth there and tells a fold from its mirror image.

#include <array>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace forensim {

using Quad = std::array<Vec3, 4>;

/// Signed dihedral angle theta (radians) of the pair (x0, x2, x3), (x1, x3, x2). 0 when a triangle is degenerate.
double dihedral_angle(const Quad& x);

/// theta and its gradient d theta / d x_i (rows 0..3; they sum to zero). Zero gradient for a degenerate pair.
struct DihedralGradient {
  double angle = 0.0;
  std::array<Vec3, 4> gradient{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
};
DihedralGradient dihedral_angle_gradient(const Quad& x);

/// angle - rest_angle wrapped into (-pi, pi].
double bending_value(const Quad& x, double rest_angle);

/// Projection (Mueller et al. 2007, eq. 8 and 9): dp_i = -k s w_i grad_i C with s = C / sum_j w_j |grad_j C|^2.
/// `w` inverse masses (>= 0), `stiffness` k in [0, 1]. Zero corrections for a degenerate pair or all fixed.
/// With equal masses sum dp_i = 0 (the gradients sum to zero): linear momentum is conserved.
std::array<Vec3, 4> project_bending(const Quad& x, const Vec4& w, double rest_angle, double stiffness);

/// Bending constraints of every interior edge of a triangle mesh (Model data, #B entries each).
struct BendingConstraints {
  std::vector<std::array<Index, 4>> quad_vertices;  ///< #B (x0, x1, x2, x3) as above
  std::vector<double> rest_angle;                   ///< #B theta_0 (radians)
  std::size_t size() const { return quad_vertices.size(); }
};

/// One constraint per edge shared by exactly two consistently oriented triangles (boundary and non-manifold
/// edges get none), rest angles from `positions`. Throws InputError naming `source` for an index out of range.
BendingConstraints make_bending_constraints(const std::vector<Vec3>& positions, const std::vector<Tri>& triangles,
                                            const std::string& source);

}  // namespace forensim
