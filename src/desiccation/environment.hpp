#pragma once
/// The surroundings of a drying body (beyond the paper, which lists them as future work): air temperature,
/// relative humidity and air speed set the equilibrium moisture phi_e and the mass-transfer coefficient h_m
/// of the evaporation boundary (Frerichs, Vidler and Gatzidis 2020, eq. 6), and a cover factor per skin face
/// models cloth and the ground a body lies on.
///
/// Relations used:
/// - Equilibrium moisture: GAB sorption isotherm X_e = X_m C K a / ((1 - K a)(1 - K a + C K a)) with the water
///   activity a = relative humidity. Defaults X_m = 0.08, C = 10, K = 0.85 (dry basis), in the range reported
///   for beef and pork at 20-40 C (e.g. Trujillo, Wiangkaew and Pham 2003/2007; Comaposada et al. 2000).
/// - Air-side mass transfer: a cylinder of diameter d across the wind, Churchill-Bernstein correlation with
///   the Sherwood number for the Nusselt number (Chilton-Colburn heat/mass analogy):
///     Sh = 0.3 + 0.62 Re^1/2 Sc^1/3 / (1 + (0.4/Sc)^2/3)^1/4 (1 + (Re/282000)^5/8)^4/5,  h_m = Sh D_va / d,
///   Re = v d / nu_air, Sc = nu_air / D_va, D_va = 2.5e-5 (T/298 K)^1.75 m^2/s (water vapour in air),
///   nu_air = 1.55e-5 (T/298 K)^1.75 m^2/s. Wind below 0.2 m/s is taken as 0.2 m/s (a body's own natural
///   convection).
/// - The skin is a vapour barrier of permeance k_skin (TissueDrying::skin_permeance_m_per_s) in series with
///   the air side: k = 1 / (1 / h_m + 1 / k_skin).
/// - The Robin condition of the diffusion solver is written in moisture content, -D dX/dn = h (X - X_e). Its
///   coefficient h is matched to the vapour flux k (rho_sat(T) - RH rho_sat(T)) of fresh, fully wet tissue:
///     h = k rho_sat(T) (1 - RH) / (rho_d0 (X0 - X_e)),
///   rho_sat from the Magnus formula (Alduchov and Eskridge 1996) and the ideal gas law, rho_d0 the dry-solid
///   density (material_laws.hpp). So a wet surface evaporates like free water and the flux falls to zero at X_e.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "desiccation/material_laws.hpp"
#include "geometry/tet_mesh.hpp"

namespace forensim {

/// GAB sorption isotherm parameters (dry basis).
struct SorptionIsotherm {
  double monolayer_moisture = 0.08;  ///< X_m, kg water / kg dry solid
  double guggenheim_c = 10.0;        ///< C
  double gab_k = 0.85;               ///< K (< 1)
};

struct DryingEnvironment {
  double air_temperature_c = 35.0;  ///< T, air temperature, degrees Celsius
  double relative_humidity = 0.3;   ///< RH (0..1); also the water activity at equilibrium
  double air_speed_m_per_s = 1.0;   ///< v, wind speed
  double body_diameter_m = 0.08;    ///< d, characteristic diameter of the limb for the correlation
  SorptionIsotherm isotherm;
  /// Evaporation factor of every uncovered skin face (1 = bare skin; < 1 = light cloth).
  double skin_cover = 1.0;
  /// Ground contact: when true, skin faces below ground_height_mm + ground_tolerance_mm whose outward normal
  /// points down (angle to -up below ground_angle_deg) are sealed (cover 0).
  bool on_ground = false;
  Vec3 up{0.0, 0.0, 1.0};            ///< unit up direction
  double ground_height_mm = 0.0;     ///< height of the ground along `up`, mm
  double ground_tolerance_mm = 3.0;  ///< contact band above the ground, mm
  double ground_angle_deg = 60.0;    ///< faces within this angle of straight down touch the ground
  /// Checks ranges; throws InputError naming `source` and the field.
  void validate(const std::string& source) const;
};

/// Saturation vapour density of water in air at `temperature_c`, kg/m^3 (Magnus formula, ideal gas).
double saturation_vapour_density_kg_per_m3(double temperature_c);

/// GAB equilibrium moisture X_e (kg water / kg dry solid) at water activity `activity` in [0, 1).
double equilibrium_moisture(const SorptionIsotherm& isotherm, double activity);

/// Air-side mass-transfer coefficient h_m (m/s) of a cylinder of env.body_diameter_m in cross flow.
double air_mass_transfer_m_per_s(const DryingEnvironment& env);

/// Vapour transfer coefficient k (m/s) of the skin and the air in series, 1 / (1 / h_m + 1 / k_skin).
double skin_vapour_transfer_m_per_s(const DryingEnvironment& env, const TissueDrying& tissue);

/// Robin coefficient h (m/s) of -D dX/dn = h (X - X_e) for `tissue` in `env` (see above).
double surface_transfer_m_per_s(const DryingEnvironment& env, const TissueDrying& tissue);

/// Cover factor (0..1) of each face: env.skin_cover, or 0 where the face lies on the ground.
/// `faces`: node triples, counter-clockwise from outside; `positions`: mesh nodes, mm.
std::vector<double> face_cover(const std::vector<Vec3>& positions, const std::vector<Tri>& faces,
                               const DryingEnvironment& env);

}  // namespace forensim
