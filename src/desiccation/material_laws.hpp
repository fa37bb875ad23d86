#pragma once
/// Material laws of drying soft tissue: how moisture sets the volume ratio, the dry-solid density and the
/// moisture diffusivity (Frerichs, Vidler and Gatzidis 2020, eqs. 7, 8, 27-30; Yang et al. 2001, Liu et al.
/// 2014, Mayor and Sereno 2004), and the elastic materials of flesh and bone.
///
/// Moisture X is on a dry basis throughout: kg of water per kg of dry solid (the paper's phi). The paper's
/// fresh arm holds 75 % water on a wet basis (section 9.2), X0 = 0.75 / 0.25 = 3.
///
/// Reconstructed forms (the transcription garbles the symbols):
/// - Volume ratio (eq. 28, the beef-slab model of Mayor and Sereno 2004 with zero porosity, i.e. ideal
///   shrinkage: the volume lost is the volume of the water lost)
///     S_v(X) = 1 + rho0 (X - X0) / (rho_w (1 + X0)),
///   rho0 the fresh tissue's bulk density, rho_w water's. S_v(X0) = 1; S_v(0) = 1 - rho0 X0 / (rho_w (1 + X0))
///   (0.205 for the defaults). `shrinkage_efficiency` (beta, 0..1) scales the loss: S_v = 1 - beta (1 - S_v).
/// - Dry-solid density (eq. 7): rho_d = rho_d0 / S_v with rho_d0 = rho0 / (1 + X0); the dry mass of a tet is
///   constant, so water content per volume is rho_d X.
/// - Diffusivity (eq. 8 reads w = w0 exp(-phi0 / phi), which is not w0 at the start): we use
///     D(X) = max(D_min, D0 exp(-b (X0 / X - 1))),
///   D0 at the initial moisture, falling steeply as the tissue dries (case hardening), b = 1 gives eq. 8's
///   shape. Effective moisture diffusivities of meat and fish during air drying are 1e-11..1e-9 m^2/s
///   (Trujillo, Wiangkaew and Pham 2007, beef: about 1e-10 m^2/s at 20-30 C; Mayor and Sereno 2004).
///   D0 = 1e-10 m^2/s. The skin is a barrier (skin_permeance_m_per_s): without it a wet surface would
///   evaporate like free water (about 25 kg/m^2/day in the default environment) and a forearm would lose
///   half its water in a day. With it the arm phantom in the hot, dry default environment loses about 30 %
///   of its mass in 60 days (Papageorgopoulou et al. 2015; tests/desiccation/slow_arm_drying.cpp).

#include "fem/corotational_solver.hpp"

namespace forensim {

/// Drying parameters of soft tissue (flesh).
struct TissueDrying {
  double initial_moisture = 3.0;                  ///< X0 (phi_0), kg water / kg dry solid (75 % wet basis)
  double initial_density_kg_per_m3 = 1060.0;      ///< rho0, bulk density of fresh soft tissue (eq. 28)
  double water_density_kg_per_m3 = 1000.0;        ///< rho_w (eq. 28)
  double shrinkage_efficiency = 1.0;              ///< beta, fraction of the ideal shrinkage (1 = eq. 28)
  double reference_diffusivity_m2_per_s = 1e-10;  ///< D0 (w_0), diffusivity at X0 (eq. 8)
  double diffusivity_drying_exponent = 1.0;       ///< b in D0 exp(-b (X0 / X - 1))
  double minimum_diffusivity_m2_per_s = 1e-13;    ///< D_min, floor for bone-dry tissue
  /// k_skin, water-vapour permeance of the (dead) skin, m/s: flux = k_skin (rho_sat - rho_air) in series with
  /// the air side (environment.hpp). 4e-5 m/s gives 4 g/m^2/h at 35 C, 30 % RH, the order of the
  /// transepidermal water loss of skin (1-10 g/m^2/h); calibrated with D0 to Papageorgopoulou et al. 2015.
  double skin_permeance_m_per_s = 4e-5;
  /// Checks ranges (positive densities and moisture, efficiency in [0, 1], S_v(0) > 0). Throws InputError
  /// naming `source`.
  void validate(const std::string& source) const;
};

/// Flesh and bone elastic materials (eqs. 25, 26). Defaults: soft tissue E = 20 kPa, nu = 0.3 (drying
/// tissue is compressible: its water leaves), 1060 kg/m^3; cortical bone E = 15 GPa, nu = 0.3, 1900 kg/m^3
/// (typical literature values, e.g. Fung 1993, "Biomechanics").
struct TissueMaterials {
  ElasticMaterial flesh{2e4, 0.3, 1060.0};
  ElasticMaterial bone{1.5e10, 0.3, 1900.0};
};

/// Wet-basis water fraction X / (1 + X) of a dry-basis moisture X (kg water / kg tissue).
double wet_basis_moisture(double moisture);
/// Dry-basis moisture of a wet-basis fraction w in [0, 1): w / (1 - w).
double dry_basis_moisture(double wet_fraction);

/// rho_d0 = rho0 / (1 + X0): kg of dry solid per m^3 of fresh tissue.
double dry_solid_density_kg_per_m3(const TissueDrying& tissue);

/// Volumetric shrinkage coefficient S_v = V / V0 of tissue at moisture X (eq. 28, times the efficiency).
/// 1 at X0, decreasing linearly to S_v(0); X is clamped to [0, X0] (no swelling).
double volume_ratio(const TissueDrying& tissue, double moisture);

/// Dry-solid density rho_d = rho_d0 / S_v, kg/m^3 (eq. 7): the capacity of the diffusion equation.
double dry_solid_density_kg_per_m3(const TissueDrying& tissue, double volume_ratio);

/// Bulk density of tissue at moisture X, kg/m^3: rho_d0 (1 + X) / S_v(X) (rho0 at X0).
double tissue_density_kg_per_m3(const TissueDrying& tissue, double moisture);

/// Moisture diffusivity D(X), m^2/s (reconstructed eq. 8, see above). D0 at X >= X0, D_min at X <= 0.
double moisture_diffusivity_m2_per_s(const TissueDrying& tissue, double moisture);

}  // namespace forensim
