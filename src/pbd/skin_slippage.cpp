#include "pbd/skin_slippage.hpp"

#include <cmath>

#include "core/error.hpp"

namespace forensim {

void SlippageLaw::validate(const std::string& source) const {
  require_input(std::isfinite(initial_stiffness) && initial_stiffness >= 0.0 && initial_stiffness <= 1.0, source,
                "initial_stiffness", "must lie in [0, 1]");
  require_input(std::isfinite(decrease_below) && decrease_below > 0.0 && decrease_below <= 1.0, source,
                "decrease_below", "must lie in (0, 1]");
  require_input(std::isfinite(zero_below) && zero_below >= 0.0 && zero_below <= decrease_below, source, "zero_below",
                "must lie in [0, decrease_below]");
}

double tracking_stiffness(double moisture_ratio, const SlippageLaw& law) {
  if (!(moisture_ratio >= law.zero_below)) return 0.0;
  if (moisture_ratio < law.decrease_below) return moisture_ratio * law.initial_stiffness / law.decrease_below;
  return law.initial_stiffness;
}

double slip_fraction(double moisture_ratio, const SlippageLaw& law) {
  if (!(moisture_ratio >= law.zero_below)) return 1.0;  // also NaN: treated as dry
  if (moisture_ratio < law.decrease_below) return 1.0 - moisture_ratio / law.decrease_below;
  return 0.0;
}

double slip_radius_mm(double moisture_ratio, const SlippageLaw& law, double r_max_mm) {
  return slip_fraction(moisture_ratio, law) * r_max_mm;
}

}  // namespace forensim
