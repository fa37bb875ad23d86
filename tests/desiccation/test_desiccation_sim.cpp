#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "desiccation/desiccation_sim.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

constexpr double hour = 3600.0;

/// A 20 x 20 x 40 mm block with a bone core along z (tets whose centroid is within 4 mm of the axis), parts:
/// 0 = lower half, 1 = upper half.
BodyModel block_body(bool with_bone) {
  BodyModel body;
  body.volume = make_box_tet_mesh(Vec3(-10, -10, 0), Vec3(10, 10, 40), 5, 5, 6);
  body.volume.tet_labels.assign(body.volume.tet_count(), tissue_flesh);
  body.part_names = {"lower", "upper"};
  body.tet_parts.resize(body.volume.tet_count());
  for (std::size_t t = 0; t < body.volume.tet_count(); ++t) {
    Vec3 c = Vec3::Zero();
    for (Index n : body.volume.tets[t]) c += body.volume.positions[static_cast<std::size_t>(n)] / 4.0;
    if (with_bone && std::hypot(c.x(), c.y()) < 4.0) body.volume.tet_labels[t] = tissue_bone;
    body.tet_parts[t] = c.z() < 20.0 ? 0 : 1;
  }
  return body;
}

DesiccationSettings fast_settings() {
  DesiccationSettings s;
  s.tissue.reference_diffusivity_m2_per_s = 1e-9;  // a small block dries noticeably in a few hours
  s.elastic.quasi_static_tolerance_mm = 1e-4;      // keeps the quick suite quick
  s.tissue.skin_permeance_m_per_s = 1.0;           // no skin barrier: dries within hours
  return s;
}

void run(DesiccationSolver& solver, DesiccationState& state, int steps, double dt) {
  for (int i = 0; i < steps; ++i) solver.step(state, dt);
}

}  // namespace

TEST(DesiccationSim, WaterIsConservedAndMoistureBounded) {
  const DesiccationModel model = make_desiccation_model(block_body(true), fast_settings());
  DesiccationState state = initial_desiccation_state(model);
  const DesiccationTotals start = desiccation_totals(model, state);
  DesiccationSolver solver(model);
  for (int i = 0; i < 6; ++i) {
    const DesiccationStepReport r = solver.step(state, 6 * hour);
    EXPECT_EQ(r.inverted_tets, 0u);
    EXPECT_GT(r.evaporated_kg, 0.0);
    EXPECT_LT(r.deformation_iterations, 20);
  }
  const DesiccationTotals end = desiccation_totals(model, state);
  EXPECT_LT(end.water_kg, 0.9 * start.water_kg);  // it did dry
  EXPECT_NEAR(start.water_kg - end.water_kg, state.evaporated_kg, 1e-8 * start.water_kg);
  EXPECT_NEAR(end.total_kg, start.total_kg - state.evaporated_kg, 1e-8 * start.total_kg);
  EXPECT_DOUBLE_EQ(end.dry_kg, start.dry_kg);
  // Parts add up to the totals.
  EXPECT_NEAR(end.part_water_kg[0] + end.part_water_kg[1], end.water_kg, 1e-12 * start.water_kg);
  EXPECT_NEAR(end.part_total_kg[0] + end.part_total_kg[1], end.total_kg, 1e-12 * start.total_kg);
  // Between equilibrium and initial moisture, on every flesh node.
  // The consistent Robin face matrix of fem/diffusion_solver (eq. 13) has positive off-diagonals, so the
  // discrete maximum principle holds only up to a small undershoot near X_e where the surface is dry.
  double lowest = 1e9, highest = -1e9;
  for (std::size_t t = 0; t < model.body.volume.tet_count(); ++t) {
    if (!model.tet_active[t]) continue;
    for (Index n : model.body.volume.tets[t]) {
      lowest = std::min(lowest, state.node_moisture[static_cast<std::size_t>(n)]);
      highest = std::max(highest, state.node_moisture[static_cast<std::size_t>(n)]);
    }
  }
  EXPECT_GE(lowest, 0.8 * model.equilibrium_moisture);
  EXPECT_LE(highest, model.settings.tissue.initial_moisture + 1e-9);
  EXPECT_LT(end.volume_mm3, start.volume_mm3);
}

TEST(DesiccationSim, BoneHoldsNoWaterAndStaysRigid) {
  const DesiccationModel model = make_desiccation_model(block_body(true), fast_settings());
  DesiccationState state = initial_desiccation_state(model);
  DesiccationSolver solver(model);
  run(solver, state, 4, 12 * hour);
  const TetMesh& mesh = model.body.volume;
  std::size_t bone = 0;
  std::vector<std::uint8_t> touches_flesh(mesh.vertex_count(), 0);
  for (std::size_t t = 0; t < mesh.tet_count(); ++t)
    if (model.tet_active[t])
      for (Index n : mesh.tets[t]) touches_flesh[static_cast<std::size_t>(n)] = 1;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (model.tet_active[t]) continue;
    ++bone;
    const double v = tet_signed_volume(state.positions[static_cast<std::size_t>(mesh.tets[t][0])],
                                       state.positions[static_cast<std::size_t>(mesh.tets[t][1])],
                                       state.positions[static_cast<std::size_t>(mesh.tets[t][2])],
                                       state.positions[static_cast<std::size_t>(mesh.tets[t][3])]);
    EXPECT_NEAR(v / model.tet_rest_volume_mm3[t], 1.0, 1e-3);
    for (Index n : mesh.tets[t])
      if (!touches_flesh[static_cast<std::size_t>(n)]) {
        EXPECT_EQ(state.node_moisture[static_cast<std::size_t>(n)], 0.0);
      }
  }
  ASSERT_GT(bone, 0u);
  const std::vector<double> x = tet_moisture(model, state);
  for (std::size_t t = 0; t < mesh.tet_count(); ++t)
    if (!model.tet_active[t]) {
      EXPECT_EQ(x[t], 0.0);
    }
}

TEST(DesiccationSim, UniformDryingGivesTheVolumeRatio) {
  DesiccationSettings settings = fast_settings();
  settings.environment.skin_cover = 0.0;  // sealed: moisture stays uniform
  const DesiccationModel model = make_desiccation_model(block_body(false), settings);
  DesiccationState state = initial_desiccation_state(model);
  const double x = 1.2;
  std::fill(state.node_moisture.begin(), state.node_moisture.end(), x);
  const double v0 = desiccation_totals(model, state).volume_mm3;
  DesiccationSolver solver(model);
  solver.step(state, hour);
  const double ratio = desiccation_totals(model, state).volume_mm3 / v0;
  EXPECT_NEAR(ratio / volume_ratio(settings.tissue, x), 1.0, 0.01);
  EXPECT_NEAR(state.evaporated_kg, 0.0, 1e-18);
}

TEST(DesiccationSim, CheckpointResumeIsIdentical) {
  const DesiccationModel model = make_desiccation_model(block_body(true), fast_settings());
  DesiccationState straight = initial_desiccation_state(model);
  {
    DesiccationSolver solver(model);
    run(solver, straight, 4, 6 * hour);
  }
  DesiccationState first = initial_desiccation_state(model);
  const auto path = test::scratch_dir("desiccation") / "checkpoint.bin";
  {
    DesiccationSolver solver(model);
    run(solver, first, 2, 6 * hour);
    write_desiccation_checkpoint(path, first);
  }
  DesiccationState resumed = read_desiccation_checkpoint(path, model.body.volume.vertex_count());
  EXPECT_EQ(resumed.step_count, 2);
  DesiccationSolver solver(model);
  run(solver, resumed, 2, 6 * hour);
  EXPECT_EQ(resumed.time_s, straight.time_s);
  EXPECT_EQ(resumed.evaporated_kg, straight.evaporated_kg);
  EXPECT_EQ(resumed.node_moisture, straight.node_moisture);
  for (std::size_t i = 0; i < straight.positions.size(); ++i) ASSERT_EQ(resumed.positions[i], straight.positions[i]);
}

TEST(DesiccationSim, CheckpointRejectsBadFiles) {
  const auto dir = test::scratch_dir("desiccation");
  DesiccationState state;
  state.node_moisture.assign(3, 1.0);
  state.positions.assign(3, Vec3::Zero());
  state.velocities.assign(3, Vec3::Zero());
  write_desiccation_checkpoint(dir / "small.bin", state);
  EXPECT_NO_THROW(read_desiccation_checkpoint(dir / "small.bin", 3));
  EXPECT_THROW(read_desiccation_checkpoint(dir / "small.bin", 4), InputError);
  std::string bytes = read_file(dir / "small.bin");
  write_file_atomic(dir / "truncated.bin", bytes.substr(0, bytes.size() - 5));
  EXPECT_THROW(read_desiccation_checkpoint(dir / "truncated.bin", 3), InputError);
  write_file_atomic(dir / "garbage.bin", "not a checkpoint at all, just some text that is long enough");
  EXPECT_THROW(read_desiccation_checkpoint(dir / "garbage.bin", 3), InputError);
  EXPECT_THROW(read_desiccation_checkpoint(dir / "missing.bin", 3), IoError);
}

TEST(DesiccationSim, DeterministicAcrossThreadCounts) {
  const DesiccationModel model = make_desiccation_model(block_body(true), fast_settings());
  std::vector<DesiccationState> results;
  for (int threads : {1, 2}) {
    set_thread_count(threads);
    DesiccationState state = initial_desiccation_state(model);
    DesiccationSolver solver(model);
    run(solver, state, 3, 6 * hour);
    results.push_back(std::move(state));
  }
  set_thread_count(0);
  EXPECT_EQ(results[0].node_moisture, results[1].node_moisture);
  EXPECT_EQ(results[0].evaporated_kg, results[1].evaporated_kg);
  for (std::size_t i = 0; i < results[0].positions.size(); ++i)
    ASSERT_EQ(results[0].positions[i], results[1].positions[i]);
}

TEST(DesiccationSim, GroundContactSlowsDrying) {
  DesiccationSettings lying = fast_settings();
  lying.environment.on_ground = true;
  lying.environment.ground_height_mm = 0.0;
  lying.environment.up = Vec3(0, 0, 1);
  const DesiccationModel free_model = make_desiccation_model(block_body(true), fast_settings());
  const DesiccationModel ground_model = make_desiccation_model(block_body(true), lying);
  std::size_t sealed = 0, bottom = 0;
  for (const RobinFace& f : ground_model.skin_faces) {
    sealed += f.cover == 0.0 ? 1 : 0;
    bool on_bottom = true;
    for (Index n : f.vertices)
      on_bottom = on_bottom && ground_model.body.volume.positions[static_cast<std::size_t>(n)].z() == 0.0;
    bottom += on_bottom ? 1 : 0;
  }
  EXPECT_EQ(sealed, bottom);  // the flesh faces of the block's bottom
  EXPECT_GT(bottom, 30u);
  DesiccationState a = initial_desiccation_state(free_model), b = initial_desiccation_state(ground_model);
  DesiccationSolver sa(free_model), sb(ground_model);
  run(sa, a, 2, 6 * hour);
  run(sb, b, 2, 6 * hour);
  EXPECT_LT(b.evaporated_kg, a.evaporated_kg);
}

TEST(DesiccationSim, RejectsBadInput) {
  const DesiccationModel model = make_desiccation_model(block_body(true), fast_settings());
  DesiccationState state = initial_desiccation_state(model);
  DesiccationSolver solver(model);
  EXPECT_THROW(solver.step(state, -1.0), InputError);
  state.node_moisture.pop_back();
  EXPECT_THROW(solver.step(state, 1.0), InputError);
  DesiccationSettings bad = fast_settings();
  bad.environment.relative_humidity = 45.0;
  EXPECT_THROW(make_desiccation_model(block_body(true), bad), InputError);
}
