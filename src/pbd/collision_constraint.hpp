#pragma once
/// Collision constraint of position-based dynamics against a surface (Mueller et al. 2007, "Position based
/// dynamics", section 3.4 and 4.3): when a particle's predicted position has gone under the volume boundary, a
/// plane constraint C(p) = n . (p - q) - h >= 0 is generated for the step through the surface point q with the
/// surface normal n (unit, outward) and allowed height h (0: on the surface; negative: a skin vertex that starts
/// under the boundary keeps its rest depth). The kernel takes the surface point's inverse mass too, so it is the
/// general two-body contact; the skin passes 0 for the volume.

#include "core/types.hpp"
#include "pbd/stretch_constraint.hpp"

namespace forensim {

/// C = n . (p - q) - height; satisfied where C >= 0.
double collision_value(const Vec3& p, const Vec3& q, const Vec3& normal, double height);

/// Projection of the inequality: nothing when C >= 0; else dp = -w_p / (w_p + w_q) k C n and
/// dq = +w_q / (w_p + w_q) k C n (dp0 is p's, dp1 is q's). Conserves linear momentum.
PairCorrection project_collision(const Vec3& p, const Vec3& q, const Vec3& normal, double w_p, double w_q,
                                 double height, double stiffness = 1.0);

}  // namespace forensim
