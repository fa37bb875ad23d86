// The arm phantom in the default (hot, dry) environment: calibration against Papageorgopoulou et al. 2015
// (about 30 % of the mass lost in the first two months), the paper's finding that the fingers dry first
// (section 9.1), and no inverted tets over the run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "body/phantom_model.hpp"
#include "desiccation/desiccation_sim.hpp"

using namespace forensim;

namespace {

constexpr double day = 86400.0;

int part_index(const BodyModel& body, const std::string& name) {
  for (std::size_t i = 0; i < body.part_names.size(); ++i)
    if (body.part_names[i] == name) return static_cast<int>(i);
  return -1;
}

}  // namespace

TEST(SlowArmDrying, CalibratedMassLossFingersFirstNoInversion) {
  const BodyModel body = make_phantom_model(phantom_model_size("arm", "small"));
  const DesiccationModel model = make_desiccation_model(body, DesiccationSettings{});
  const TetMesh& mesh = model.body.volume;
  const double rho_d0 = dry_solid_density_kg_per_m3(model.settings.tissue);

  // Fingers (all five digits) and the middle third of the forearm along x (distal axis).
  std::vector<std::uint8_t> finger(mesh.tet_count(), 0), mid_forearm(mesh.tet_count(), 0);
  const int forearm = part_index(model.body, "forearm");
  ASSERT_GE(forearm, 0);
  double x_min = 1e9, x_max = -1e9;
  std::vector<double> cx(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    for (Index n : mesh.tets[t]) cx[t] += mesh.positions[static_cast<std::size_t>(n)].x() / 4.0;
    if (model.body.tet_parts[t] == forearm) {
      x_min = std::min(x_min, cx[t]);
      x_max = std::max(x_max, cx[t]);
    }
  }
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const std::string& name = model.body.part_names[static_cast<std::size_t>(model.body.tet_parts[t])];
    finger[t] = name == "thumb" || name == "index" || name == "middle" || name == "ring" || name == "little";
    mid_forearm[t] = model.body.tet_parts[t] == forearm && cx[t] > x_min + (x_max - x_min) / 3.0 &&
                     cx[t] < x_max - (x_max - x_min) / 3.0;
  }
  auto water = [&](const DesiccationState& s, const std::vector<std::uint8_t>& mask) {
    const std::vector<double> x = tet_moisture(model, s);
    double w = 0.0;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
      if (mask[t] && model.tet_active[t]) w += rho_d0 * model.tet_rest_volume_mm3[t] * x[t];
    return w;
  };

  DesiccationState state = initial_desiccation_state(model);
  DesiccationSolver solver(model);
  const DesiccationTotals start = desiccation_totals(model, state);
  const double finger0 = water(state, finger), forearm0 = water(state, mid_forearm);
  double forearm_when_fingers_at_20 = -1.0;
  const double dt = 0.5 * day;
  std::printf("day  mass%%  water%%  volume%%  fingers%%  mid-forearm%%\n");
  DesiccationTotals day60;
  for (int i = 1; i <= 240 && (i <= 120 || forearm_when_fingers_at_20 < 0.0); ++i) {
    const DesiccationStepReport r = solver.step(state, dt, i % 4 == 0);  // shape every 2 days
    ASSERT_EQ(r.inverted_tets, 0u) << "step " << i;
    const double f = water(state, finger) / finger0, m = water(state, mid_forearm) / forearm0;
    if (forearm_when_fingers_at_20 < 0.0 && f <= 0.2) forearm_when_fingers_at_20 = m;
    if (i == 120) day60 = desiccation_totals(model, state);
    if (i % 10 == 0) {
      const DesiccationTotals now = desiccation_totals(model, state);
      std::printf("%4.0f  %5.1f  %6.1f  %7.1f  %8.1f  %12.1f\n", state.time_s / day,
                  100.0 * now.total_kg / start.total_kg, 100.0 * now.water_kg / start.water_kg,
                  100.0 * now.volume_mm3 / start.volume_mm3, 100.0 * f, 100.0 * m);
    }
  }
  const DesiccationTotals end = desiccation_totals(model, state);
  const double mass_lost = 1.0 - day60.total_kg / start.total_kg;
  std::printf("60 days: mass lost %.1f %% (Papageorgopoulou et al. 2015: about 30 %%)\n", 100.0 * mass_lost);
  EXPECT_GT(mass_lost, 0.22);
  EXPECT_LT(mass_lost, 0.38);
  EXPECT_NEAR(start.water_kg - end.water_kg, state.evaporated_kg, 1e-8 * start.water_kg);
  // Fingers dry first: whole fingers (drier than their tips only later) reach 20 % while the mid-forearm
  // still holds at least half of its water.
  ASSERT_GE(forearm_when_fingers_at_20, 0.0) << "fingers never reached 20 % of their water";
  EXPECT_GE(forearm_when_fingers_at_20, 0.5);
}
