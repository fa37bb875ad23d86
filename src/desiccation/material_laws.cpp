#include "desiccation/material_laws.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace forensim {

void TissueDrying::validate(const std::string& source) const {
  auto positive = [&](double v, const char* name) {
    require_input(std::isfinite(v) && v > 0.0, source, name, "must be a positive number");
  };
  positive(initial_moisture, "initial_moisture");
  positive(initial_density_kg_per_m3, "initial_density_kg_per_m3");
  positive(water_density_kg_per_m3, "water_density_kg_per_m3");
  positive(reference_diffusivity_m2_per_s, "reference_diffusivity_m2_per_s");
  positive(minimum_diffusivity_m2_per_s, "minimum_diffusivity_m2_per_s");
  positive(skin_permeance_m_per_s, "skin_permeance_m_per_s");
  require_input(std::isfinite(diffusivity_drying_exponent) && diffusivity_drying_exponent >= 0.0, source,
                "diffusivity_drying_exponent", "must be a number >= 0");
  require_input(std::isfinite(shrinkage_efficiency) && shrinkage_efficiency >= 0.0 && shrinkage_efficiency <= 1.0,
                source, "shrinkage_efficiency", "must be in [0, 1]");
  require_input(volume_ratio(*this, 0.0) > 0.01, source, "initial_density_kg_per_m3",
                "fully dried tissue would keep less than 1 % of its volume (eq. 28); check the densities");
}

double wet_basis_moisture(double moisture) {
  return moisture / (1.0 + moisture);
}

double dry_basis_moisture(double wet_fraction) {
  return wet_fraction / (1.0 - wet_fraction);
}

double dry_solid_density_kg_per_m3(const TissueDrying& tissue) {
  return tissue.initial_density_kg_per_m3 / (1.0 + tissue.initial_moisture);
}

double volume_ratio(const TissueDrying& tissue, double moisture) {
  const double x = std::clamp(moisture, 0.0, tissue.initial_moisture);
  const double ideal = 1.0 + tissue.initial_density_kg_per_m3 * (x - tissue.initial_moisture) /
                                 (tissue.water_density_kg_per_m3 * (1.0 + tissue.initial_moisture));
  return 1.0 - tissue.shrinkage_efficiency * (1.0 - ideal);
}

double dry_solid_density_kg_per_m3(const TissueDrying& tissue, double ratio) {
  return dry_solid_density_kg_per_m3(tissue) / ratio;
}

double tissue_density_kg_per_m3(const TissueDrying& tissue, double moisture) {
  const double x = std::max(moisture, 0.0);
  return dry_solid_density_kg_per_m3(tissue) * (1.0 + x) / volume_ratio(tissue, x);
}

double moisture_diffusivity_m2_per_s(const TissueDrying& tissue, double moisture) {
  if (moisture >= tissue.initial_moisture)
    return std::max(tissue.reference_diffusivity_m2_per_s, tissue.minimum_diffusivity_m2_per_s);
  if (moisture <= 0.0) return tissue.minimum_diffusivity_m2_per_s;
  const double d = tissue.reference_diffusivity_m2_per_s *
                   std::exp(-tissue.diffusivity_drying_exponent * (tissue.initial_moisture / moisture - 1.0));
  return std::max(d, tissue.minimum_diffusivity_m2_per_s);
}

}  // namespace forensim
