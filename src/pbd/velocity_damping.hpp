#pragma once
/// Velocity damping of position-based dynamics that keeps the rigid-body motion (Mueller et al. 2007, "Position
/// based dynamics", section 3.5): each velocity moves a fraction k_damping of the way to the rigid motion
/// v_cm + omega x r_i of all particles (centre-of-mass velocity and angular velocity from the momenta). The
/// paper's wrinkle control (Frerichs, Vidler and Gatzidis 2020, section 8.2 and Figure 8) is this k_damping.
/// A skin tied to a body should keep the body's motion rather than its own rigid motion (that one would let the
/// skin swing around the body undamped), so the skin damps its velocity relative to the volume under it by
/// default (damp_relative_velocities); Mueller's form stays available.

#include <vector>

#include "core/types.hpp"

namespace forensim {

/// Damps `velocities` (#N, mm/s) in place: v_i += k (v_cm + omega x (x_i - x_cm) - v_i), with masses 1 / w_i
/// (particles with w_i = 0 are left as they are and do not count). `k_damping` in [0, 1]: 0 leaves the
/// velocities, 1 leaves only the rigid motion. The sums are deterministic (fixed blocks added in order), so
/// the result does not depend on the thread count.
void damp_velocities(const std::vector<Vec3>& positions, const std::vector<double>& inverse_masses,
                     std::vector<Vec3>& velocities, double k_damping);

/// Damps `velocities` (#N) towards `frame_velocities` (#N, e.g. the velocity of each skin vertex's tracking point
/// on the volume): v_i = u_i + (1 - k) (v_i - u_i). `k_damping` in [0, 1].
void damp_relative_velocities(std::vector<Vec3>& velocities, const std::vector<Vec3>& frame_velocities,
                              double k_damping);

}  // namespace forensim
