#pragma once
/// Skin slippage (Frerichs, Vidler and Gatzidis 2020, section 8.2, eq. 35): as the skin dries, the connection
/// between epidermis and dermis weakens, so the stiffness of a vertex's tracking constraint falls with its surface
/// moisture below a threshold tau_d and is zero below a lower one tau_n (the dry skin then moves only by its own
/// constraints and external forces).

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

}  // namespace forensim
