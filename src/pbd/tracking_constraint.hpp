#pragma once
/// Tracking constraint between a skin vertex p_i and its tracking point t_i on the deforming volume's boundary
/// (Frerichs, Vidler and Gatzidis 2020, section 8.2, eqs. 32-34, after the attachment constraints of Mueller and
/// Chentanez 2010, "Wrinkle meshes"): C(p, t) = |t - p| - r <= 0, a one-sided distance constraint that acts only
/// when the skin is farther than the radius r from its tracking point.
///
/// Two uses (section 8.2): an outward-facing connection (the vertex has gone under the boundary) is projected
/// as a one-sided attachment with stiffness 1 and a constant radius; an inward-facing one gives a pulling
/// correction (eq. 34) that is added to the skin velocity before damping, with the radius r_j of eq. 33
/// (skin_slippage.hpp). The kernels take both points' inverse masses so that they are the general two-body
/// constraint; the skin passes 0 for the tracking point, which the volume moves.

#include "core/types.hpp"
#include "pbd/stretch_constraint.hpp"

namespace forensim {

/// C = |t - p| - radius (eq. 32); the constraint is satisfied where C <= 0.
double tracking_value(const Vec3& p, const Vec3& t, double radius);

/// Projection of the one-sided constraint: nothing when C <= 0; else, with n = (p - t) / |p - t|,
/// dp = -w_p / (w_p + w_t) k C n and dt = +w_t / (w_p + w_t) k C n (dp0 is p's, dp1 is t's). `stiffness` k in
/// [0, 1]. Conserves linear momentum (m_p dp + m_t dt = 0).
PairCorrection project_tracking(const Vec3& p, const Vec3& t, double w_p, double w_t, double radius, double stiffness);

/// The inward-facing connection of a skin vertex p to its fixed anchor a in one pass (w_t = 0): p moves towards a
/// to |p - a| - k C with C = |p - a| - radius when C > 0 (project_tracking), and then no farther than `bound`
/// (>= 0, stiffness 1) from a. Returns p's correction.
Vec3 project_tracking_bounded(const Vec3& p, const Vec3& a, double radius, double stiffness, double bound);

/// The pulling correction of eq. 34 for a skin vertex whose tracking point does not move (w_t = 0):
/// -k C n when |t - p| > r, else zero; the caller adds it to the velocity (divided by the time step).
Vec3 tracking_pull(const Vec3& p, const Vec3& t, double radius, double stiffness);

}  // namespace forensim
