#pragma once
/// Skin slippage (Frerichs, Vidler and Gatzidis 2020, section 8.2, eqs. 33 and 35): as the skin dries, the
/// connection between epidermis and dermis weakens. Two quantities of a skin vertex's tracking constraint follow
/// from its moisture ratio m:
/// - the stiffness k_j of the pull towards the tracked point (eq. 35): k_t for wet skin, falling in proportion to
///   m below a threshold tau_d, zero below a lower one tau_n (the dry skin is then no longer pulled: it moves by
///   its own constraints and external forces);
/// - the radius r_j within which the skin may slide and lift off without being pulled (eq. 33,
///   r_j = (1 - k_j) r_max): 0 for wet skin, growing as the stiffness falls, r_max once the stiffness is zero.
///   forensim writes it r_j = (1 - k_j / k_t) r_max, the paper's form for its k_t = 1, so that fresh skin starts
///   "close to zero" whatever k_t is.
/// r_max is "the maximum radius a vertex is allowed to move away from the volume boundary" (section 8.2): the
/// skin simulation holds every inward-facing connection within r_max however dry the skin is, so r_max sets how
/// far dried skin can slide and lift off, and so the size of its wrinkles (Figure 8).

#include <string>

namespace forensim {

/// Thresholds and initial stiffness of eq. 35. Moisture here is the skin vertex's moisture ratio m_i in [0, 1]
/// (current / initial moisture content).
struct SlippageLaw {
  double initial_stiffness = 1.0;  ///< k_t, tracking stiffness of fresh skin, in [0, 1] (the paper gives none)
  double decrease_below = 0.3;     ///< tau_d: below it the stiffness falls in proportion to m_i
  double zero_below = 0.1;         ///< tau_n: below it the stiffness is 0 (0 <= tau_n <= tau_d)
  /// Throws InputError naming `source` for a value out of range.
  void validate(const std::string& source) const;
};

/// k_j of eq. 35: k_t when m >= tau_d; m k_t / tau_d when tau_n <= m < tau_d; 0 when m < tau_n. (The
/// transcribed equation lists the middle case first as "m_i <= tau_d"; it applies between the two thresholds.)
double tracking_stiffness(double moisture_ratio, const SlippageLaw& law);

/// Slip fraction s = 1 - k_j / k_t of eq. 35's stiffness, from the moisture alone (so also for k_t = 0): 0 when
/// m >= tau_d, 1 - m / tau_d between the thresholds, 1 when m < tau_n. Non-increasing in m, in [0, 1].
double slip_fraction(double moisture_ratio, const SlippageLaw& law);

/// r_j of eq. 33 (mm): slip_fraction(m) r_max_mm. 0 for wet skin, r_max_mm for skin drier than tau_n.
double slip_radius_mm(double moisture_ratio, const SlippageLaw& law, double r_max_mm);

}  // namespace forensim
