#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "desiccation/environment.hpp"

using namespace forensim;

TEST(DryingEnvironment, SaturationVapourDensityKnownValues) {
  // Steam tables: 0.0173 kg/m^3 at 20 C, 0.0304 at 30 C, 0.0512 at 40 C.
  EXPECT_NEAR(saturation_vapour_density_kg_per_m3(20.0), 0.0173, 0.0003);
  EXPECT_NEAR(saturation_vapour_density_kg_per_m3(30.0), 0.0304, 0.0005);
  EXPECT_NEAR(saturation_vapour_density_kg_per_m3(40.0), 0.0512, 0.0008);
}

TEST(DryingEnvironment, GabIsothermShape) {
  const SorptionIsotherm iso;
  EXPECT_DOUBLE_EQ(equilibrium_moisture(iso, 0.0), 0.0);
  double previous = 0.0;
  for (int i = 1; i < 20; ++i) {
    const double x = equilibrium_moisture(iso, i / 20.0);
    EXPECT_GT(x, previous);
    previous = x;
  }
  // The monolayer is reached at moderate activity (a = 1 / (K (1 + sqrt C)) gives X_m exactly for GAB).
  const double a_m = 1.0 / (iso.gab_k * (1.0 + std::sqrt(iso.guggenheim_c)));
  EXPECT_NEAR(equilibrium_moisture(iso, a_m), iso.monolayer_moisture, 1e-12);
  // Dry air keeps the tissue far below its fresh moisture (X0 = 3).
  EXPECT_LT(equilibrium_moisture(iso, 0.3), 0.2);
}

TEST(DryingEnvironment, MassTransferGrowsWithWindAndDryness) {
  DryingEnvironment env;
  const double still = (env.air_speed_m_per_s = 0.0, air_mass_transfer_m_per_s(env));
  const double breeze = (env.air_speed_m_per_s = 1.0, air_mass_transfer_m_per_s(env));
  const double wind = (env.air_speed_m_per_s = 5.0, air_mass_transfer_m_per_s(env));
  EXPECT_LT(still, breeze);
  EXPECT_LT(breeze, wind);
  // Cylinder of 8 cm at 1 m/s: Re ~ 5000, Sh ~ 35, h_m ~ 1e-2 m/s.
  EXPECT_GT(breeze, 5e-3);
  EXPECT_LT(breeze, 2e-2);
  env.air_speed_m_per_s = 1.0;
  const TissueDrying tissue;
  const double h_dry = (env.relative_humidity = 0.2, surface_transfer_m_per_s(env, tissue));
  const double h_humid = (env.relative_humidity = 0.8, surface_transfer_m_per_s(env, tissue));
  EXPECT_GT(h_dry, h_humid);
  // Flux of fresh skin: h rho_d0 (X0 - X_e) = k rho_sat (1 - RH), k the skin and air resistances in series.
  const double k = skin_vapour_transfer_m_per_s(env, tissue);
  EXPECT_LT(k, tissue.skin_permeance_m_per_s);
  EXPECT_LT(k, air_mass_transfer_m_per_s(env));
  EXPECT_NEAR(1.0 / k, 1.0 / tissue.skin_permeance_m_per_s + 1.0 / air_mass_transfer_m_per_s(env), 1e-9 / k);
  env.relative_humidity = 0.3;
  const double x_e = equilibrium_moisture(env.isotherm, 0.3);
  EXPECT_NEAR(surface_transfer_m_per_s(env, tissue) * dry_solid_density_kg_per_m3(tissue) * (3.0 - x_e),
              k * saturation_vapour_density_kg_per_m3(env.air_temperature_c) * 0.7, 1e-15);
}

TEST(DryingEnvironment, GroundSealsDownwardFacesOnly) {
  const std::vector<Vec3> p{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}, {10, 0, 10}, {0, 10, 10}};
  const std::vector<Tri> faces{{0, 2, 1}, {3, 4, 5}, {0, 1, 4}};  // down at z=0, up at z=10, side
  DryingEnvironment env;
  env.skin_cover = 0.8;
  std::vector<double> cover = face_cover(p, faces, env);
  EXPECT_EQ(cover, (std::vector<double>{0.8, 0.8, 0.8}));
  env.on_ground = true;
  cover = face_cover(p, faces, env);
  EXPECT_EQ(cover, (std::vector<double>{0.0, 0.8, 0.8}));
  env.ground_height_mm = -20.0;  // ground far below: nothing touches it
  cover = face_cover(p, faces, env);
  EXPECT_EQ(cover, (std::vector<double>{0.8, 0.8, 0.8}));
}

TEST(DryingEnvironment, ValidateRejectsPercentHumidity) {
  DryingEnvironment env;
  EXPECT_NO_THROW(env.validate("test"));
  env.relative_humidity = 30.0;
  EXPECT_THROW(env.validate("test"), InputError);
  env = DryingEnvironment{};
  env.air_speed_m_per_s = -1.0;
  EXPECT_THROW(env.validate("test"), InputError);
}
