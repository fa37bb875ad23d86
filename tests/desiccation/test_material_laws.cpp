#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "desiccation/material_laws.hpp"

using namespace forensim;

TEST(MaterialLaws, VolumeRatioIsOneAtStartAndIdealShrinkageWhenDry) {
  const TissueDrying tissue;
  EXPECT_DOUBLE_EQ(volume_ratio(tissue, tissue.initial_moisture), 1.0);
  // Fully dry: the volume of the water lost is gone: 1 - (water mass / rho_w) / V0.
  const double water_fraction_by_volume =
      tissue.initial_density_kg_per_m3 * wet_basis_moisture(tissue.initial_moisture) / tissue.water_density_kg_per_m3;
  EXPECT_NEAR(volume_ratio(tissue, 0.0), 1.0 - water_fraction_by_volume, 1e-12);
  EXPECT_NEAR(volume_ratio(tissue, 0.0), 0.205, 1e-12);
  // No swelling above X0, clamped below 0.
  EXPECT_DOUBLE_EQ(volume_ratio(tissue, 5.0), 1.0);
  EXPECT_DOUBLE_EQ(volume_ratio(tissue, -1.0), volume_ratio(tissue, 0.0));
  TissueDrying half = tissue;
  half.shrinkage_efficiency = 0.5;
  EXPECT_NEAR(1.0 - volume_ratio(half, 1.0), 0.5 * (1.0 - volume_ratio(tissue, 1.0)), 1e-12);
}

TEST(MaterialLaws, MonotoneInMoisture) {
  const TissueDrying tissue;
  double previous_ratio = 0.0, previous_d = 0.0;
  for (int i = 0; i <= 30; ++i) {
    const double x = tissue.initial_moisture * i / 30.0;
    const double ratio = volume_ratio(tissue, x);
    const double d = moisture_diffusivity_m2_per_s(tissue, x);
    EXPECT_GT(ratio, previous_ratio);
    EXPECT_GE(d, previous_d);
    EXPECT_GE(d, tissue.minimum_diffusivity_m2_per_s);
    EXPECT_LE(d, tissue.reference_diffusivity_m2_per_s);
    previous_ratio = ratio;
    previous_d = d;
  }
}

TEST(MaterialLaws, DiffusivityLimitsAndUnits) {
  const TissueDrying tissue;
  EXPECT_DOUBLE_EQ(moisture_diffusivity_m2_per_s(tissue, tissue.initial_moisture), 1e-10);
  EXPECT_DOUBLE_EQ(moisture_diffusivity_m2_per_s(tissue, 0.0), tissue.minimum_diffusivity_m2_per_s);
  // Half the initial moisture: D0 exp(-1) (eq. 8's shape with b = 1).
  EXPECT_NEAR(moisture_diffusivity_m2_per_s(tissue, 1.5), 1e-10 * std::exp(-1.0), 1e-22);
  // Within the literature range for meat drying, m^2/s.
  EXPECT_GE(tissue.reference_diffusivity_m2_per_s, 1e-11);
  EXPECT_LT(tissue.reference_diffusivity_m2_per_s, 1e-9);
}

TEST(MaterialLaws, DensitiesConserveDryMass) {
  const TissueDrying tissue;
  EXPECT_NEAR(dry_solid_density_kg_per_m3(tissue), 265.0, 1e-12);
  EXPECT_NEAR(tissue_density_kg_per_m3(tissue, tissue.initial_moisture), 1060.0, 1e-9);
  for (double x : {0.0, 0.5, 1.5, 2.9}) {
    const double ratio = volume_ratio(tissue, x);
    // Dry mass per initial volume is fixed: rho_d * S_v = rho_d0 (eq. 7).
    EXPECT_NEAR(dry_solid_density_kg_per_m3(tissue, ratio) * ratio, 265.0, 1e-9);
    // Bulk density = (dry + water mass) / volume.
    EXPECT_NEAR(tissue_density_kg_per_m3(tissue, x), 265.0 * (1.0 + x) / ratio, 1e-9);
  }
  // Dried tissue is denser than fresh (water is lighter than the solids).
  EXPECT_GT(tissue_density_kg_per_m3(tissue, 0.0), tissue_density_kg_per_m3(tissue, 3.0));
}

TEST(MaterialLaws, WetDryBasisRoundTrip) {
  EXPECT_DOUBLE_EQ(wet_basis_moisture(3.0), 0.75);
  EXPECT_DOUBLE_EQ(dry_basis_moisture(0.75), 3.0);
}

TEST(MaterialLaws, ValidateRejectsBadParameters) {
  TissueDrying tissue;
  EXPECT_NO_THROW(tissue.validate("test"));
  tissue.initial_moisture = -1.0;
  EXPECT_THROW(tissue.validate("test"), InputError);
  tissue = TissueDrying{};
  tissue.shrinkage_efficiency = 1.5;
  EXPECT_THROW(tissue.validate("test"), InputError);
  tissue = TissueDrying{};
  tissue.water_density_kg_per_m3 = 500.0;  // would shrink below zero volume
  EXPECT_THROW(tissue.validate("test"), InputError);
}

TEST(MaterialLaws, TissueMaterialDefaults) {
  const TissueMaterials m;
  EXPECT_GT(m.bone.youngs_modulus_pa, 1e5 * m.flesh.youngs_modulus_pa);
  EXPECT_LT(m.flesh.poisson_ratio, 0.5);
  EXPECT_GT(m.bone.density_kg_per_m3, m.flesh.density_kg_per_m3);
}
