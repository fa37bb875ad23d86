#include "desiccation/environment.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace forensim {

namespace {
constexpr double kelvin = 273.15;
constexpr double water_molar_mass = 0.018015;  // kg/mol
constexpr double gas_constant = 8.314462618;   // J/(mol K)
}  // namespace

void DryingEnvironment::validate(const std::string& source) const {
  require_input(std::isfinite(air_temperature_c) && air_temperature_c > -40.0 && air_temperature_c < 80.0, source,
                "temperature", "must be between -40 and 80 C");
  require_input(std::isfinite(relative_humidity) && relative_humidity >= 0.0 && relative_humidity < 1.0, source,
                "humidity", "must be in [0, 1) (a fraction, not percent)");
  require_input(std::isfinite(air_speed_m_per_s) && air_speed_m_per_s >= 0.0 && air_speed_m_per_s < 100.0, source,
                "wind", "must be between 0 and 100 m/s");
  require_input(std::isfinite(body_diameter_m) && body_diameter_m > 0.0, source, "body_diameter_m", "must be positive");
  require_input(std::isfinite(skin_cover) && skin_cover >= 0.0 && skin_cover <= 1.0, source, "skin_cover",
                "must be in [0, 1]");
  require_input(
      isotherm.monolayer_moisture > 0.0 && isotherm.guggenheim_c > 0.0 && isotherm.gab_k > 0.0 && isotherm.gab_k < 1.0,
      source, "isotherm", "needs X_m > 0, C > 0 and 0 < K < 1");
  require_input(up.allFinite() && up.norm() > 0.0, source, "up", "must be a non-zero direction");
}

double saturation_vapour_density_kg_per_m3(double temperature_c) {
  const double p_sat_pa = 610.94 * std::exp(17.625 * temperature_c / (temperature_c + 243.04));
  return p_sat_pa * water_molar_mass / (gas_constant * (temperature_c + kelvin));
}

double equilibrium_moisture(const SorptionIsotherm& iso, double activity) {
  const double a = std::clamp(activity, 0.0, 0.999);
  const double ka = iso.gab_k * a;
  return iso.monolayer_moisture * iso.guggenheim_c * ka / ((1.0 - ka) * (1.0 - ka + iso.guggenheim_c * ka));
}

double air_mass_transfer_m_per_s(const DryingEnvironment& env) {
  const double t_ratio = (env.air_temperature_c + kelvin) / 298.15;
  const double d_va = 2.5e-5 * std::pow(t_ratio, 1.75);
  const double nu = 1.55e-5 * std::pow(t_ratio, 1.75);
  const double v = std::max(env.air_speed_m_per_s, 0.2);
  const double re = v * env.body_diameter_m / nu;
  const double sc = nu / d_va;
  const double sh = 0.3 + 0.62 * std::sqrt(re) * std::cbrt(sc) / std::pow(1.0 + std::pow(0.4 / sc, 2.0 / 3.0), 0.25) *
                              std::pow(1.0 + std::pow(re / 282000.0, 0.625), 0.8);
  return sh * d_va / env.body_diameter_m;
}

double skin_vapour_transfer_m_per_s(const DryingEnvironment& env, const TissueDrying& tissue) {
  return 1.0 / (1.0 / air_mass_transfer_m_per_s(env) + 1.0 / tissue.skin_permeance_m_per_s);
}

double surface_transfer_m_per_s(const DryingEnvironment& env, const TissueDrying& tissue) {
  const double x_e = equilibrium_moisture(env.isotherm, env.relative_humidity);
  const double drive = std::max(tissue.initial_moisture - x_e, 1e-6);
  return skin_vapour_transfer_m_per_s(env, tissue) * saturation_vapour_density_kg_per_m3(env.air_temperature_c) *
         (1.0 - env.relative_humidity) / (dry_solid_density_kg_per_m3(tissue) * drive);
}

std::vector<double> face_cover(const std::vector<Vec3>& positions, const std::vector<Tri>& faces,
                               const DryingEnvironment& env) {
  std::vector<double> cover(faces.size(), env.skin_cover);
  if (!env.on_ground) return cover;
  const Vec3 up = env.up.normalized();
  const double cos_limit = std::cos(env.ground_angle_deg * 3.14159265358979323846 / 180.0);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Vec3& a = positions[static_cast<std::size_t>(faces[f][0])];
    const Vec3& b = positions[static_cast<std::size_t>(faces[f][1])];
    const Vec3& c = positions[static_cast<std::size_t>(faces[f][2])];
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    if (len <= 0.0) continue;
    const double height = ((a + b + c) / 3.0).dot(up);
    if (height <= env.ground_height_mm + env.ground_tolerance_mm && -n.dot(up) / len >= cos_limit) cover[f] = 0.0;
  }
  return cover;
}

}  // namespace forensim
