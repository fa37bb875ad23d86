#include "pbd/skin_simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "body/tracking.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "pbd/tracking_constraint.hpp"
#include "pbd/wrinkle_measure.hpp"
#include "pbd_test_models.hpp"

using namespace forensim;

namespace {

constexpr double dt = 1.0 / 30.0;

const BodyModel& sphere() {
  static const BodyModel body = test::sphere_body();
  return body;
}

double max_displacement(const SkinState& s, const SkinModel& m) {
  double d = 0.0;
  for (std::size_t i = 0; i < s.positions.size(); ++i)
    d = std::max(d, (s.positions[i] - m.vertex_rest_position[i]).norm());
  return d;
}

double kinetic_energy(const SkinState& s, const SkinModel& m) {
  double e = 0.0;
  for (std::size_t i = 0; i < s.velocities.size(); ++i)
    e += 0.5 * s.velocities[i].squaredNorm() / m.vertex_inverse_mass[i];
  return e;
}

/// Triangles whose normal points into the ball (towards the centre): inverted skin.
std::size_t inverted_triangles(const SkinState& s, const SkinModel& m) {
  std::size_t count = 0;
  for (const Tri& t : m.triangles) {
    const Vec3& a = s.positions[t[0]];
    const Vec3 n = (s.positions[t[1]] - a).cross(s.positions[t[2]] - a);
    const Vec3 centroid = (a + s.positions[t[1]] + s.positions[t[2]]) / 3.0;
    if (n.dot(centroid) <= 0.0) ++count;
  }
  return count;
}

/// Runs `steps` steps with the ball shrinking linearly from 1 to `final_scale` and the moisture from 1 to
/// `final_moisture`.
SkinState run_shrinking(const SkinModel& model, int steps, double final_scale, double final_moisture,
                        std::vector<Vec3>* nodes_out = nullptr) {
  SkinSimulation sim(model);
  SkinState state = initial_skin_state(model);
  std::vector<Vec3> nodes;
  for (int s = 1; s <= steps; ++s) {
    const double f = static_cast<double>(s) / steps;
    nodes = test::scaled_nodes(sphere().volume, 1.0 + (final_scale - 1.0) * f);
    const std::vector<double> moisture(model.vertex_count(), 1.0 + (final_moisture - 1.0) * f);
    sim.step(state, nodes, moisture, dt);
  }
  if (nodes_out) *nodes_out = nodes;
  return state;
}

}  // namespace

TEST(SkinSimulation, StaysPutWithTheVolumeStillAndMoistureConstant) {
  for (int set = 0; set < 3; ++set) {
    SkinSettings settings;
    settings.wrinkle = WrinkleControls::figure8(set);
    const SkinModel model = make_skin_model(sphere(), settings);
    SkinSimulation sim(model);
    SkinState state = initial_skin_state(model);
    SkinStepReport report;
    for (int s = 0; s < 60; ++s)
      report = sim.step(state, sphere().volume.positions, std::vector<double>(model.vertex_count(), 1.0), dt);
    // Fresh skin on the still volume: the rest state satisfies every constraint, so nothing moves at all.
    EXPECT_LT(max_displacement(state, model), 1e-9) << "set " << set;
    EXPECT_EQ(report.pulled, 0u);
    // Partly dried skin held at that moisture: without skin shrinkage its rest state is still an equilibrium.
    SkinSettings no_shrinkage = settings;
    no_shrinkage.skin_shrinkage = 0.0;
    const SkinModel dried = make_skin_model(sphere(), no_shrinkage);
    SkinSimulation dried_sim(dried);
    SkinState dried_state = initial_skin_state(dried);
    for (int s = 0; s < 60; ++s)
      dried_sim.step(dried_state, sphere().volume.positions, std::vector<double>(dried.vertex_count(), 0.7), dt);
    EXPECT_LT(max_displacement(dried_state, dried), 1e-9) << "set " << set;
  }
}

TEST(SkinSimulation, PerturbedSkinSettlesWithoutWaves) {
  SkinSettings settings;
  settings.wrinkle = WrinkleControls::figure8(2);  // the least damped set
  const SkinModel model = make_skin_model(sphere(), settings);
  SkinSimulation sim(model);
  SkinState state = initial_skin_state(model);
  std::mt19937 rng(9);
  std::normal_distribution<double> kick(0.0, 2.0);  // mm/s
  for (Vec3& v : state.velocities) v = Vec3(kick(rng), kick(rng), kick(rng));
  const std::vector<double> moisture(model.vertex_count(), 1.0);
  const double e0 = kinetic_energy(state, model);
  std::vector<double> energy;
  for (int s = 0; s < 150; ++s) {
    sim.step(state, sphere().volume.positions, moisture, dt);
    energy.push_back(kinetic_energy(state, model));
  }
  // The motion dies out and the skin comes to rest near where it was.
  EXPECT_LT(energy.back(), 1e-6 * e0);
  EXPECT_LT(*std::max_element(energy.begin() + 50, energy.end()), 1e-2 * e0);
  // Each vertex stays within reach of its tracking point: |x - x_rest| <= |x - t| + |t - x_rest| <= r_j + l_i,
  // with r_j = l_i for fresh skin.
  for (std::size_t i = 0; i < state.positions.size(); ++i) {
    const double l = model.tracking.rest_distance[i];
    EXPECT_LE((state.positions[i] - model.vertex_rest_position[i]).norm(), 2.0 * l + 1e-3) << "vertex " << i;
  }
}

TEST(SkinSimulation, TrackingHoldsTheSkinWithinTheRadius) {
  SkinSettings settings;
  settings.skin_shrinkage = 0.0;  // the skin's own shrinkage would pull it off its tracking points
  settings.wrinkle = WrinkleControls::figure8(1);
  const SkinModel model = make_skin_model(sphere(), settings);
  SkinSimulation sim(model);
  SkinState state = initial_skin_state(model);
  // The volume moves 1 mm sideways (a rigid motion the skin can follow exactly) and the skin partly dries.
  std::vector<Vec3> nodes = sphere().volume.positions;
  for (Vec3& p : nodes) p += Vec3(1.0, 0.0, 0.0);
  const std::vector<double> moisture(model.vertex_count(), 0.2);
  SkinStepReport report;
  for (int s = 0; s < 150; ++s) report = sim.step(state, nodes, moisture, dt);
  const std::vector<Vec3> t = tracking_points(model.tracking, nodes);
  ASSERT_GT(tracking_stiffness(0.2, settings.slippage), 0.0);
  const double r = slip_radius_mm(0.2, settings.slippage, model.r_max_mm);
  ASSERT_GT(r, 0.0);
  ASSERT_LT(r, model.r_max_mm);
  double worst = -INFINITY;
  for (std::size_t i = 0; i < t.size(); ++i)
    worst = std::max(worst, tracking_value(state.positions[i], t[i] + model.vertex_tracking_offset[i], r));
  EXPECT_LT(worst, 0.02 * model.r_max_mm) << "a skin vertex is farther than r_j from its anchor";
  EXPECT_LT(report.max_tracking_excess_mm, 0.02 * model.r_max_mm);
  EXPECT_EQ(report.slipped, 0u);
}

TEST(SkinSimulation, SlippedSkinSlidesWithinTheMaximumRadius) {
  SkinSettings settings;
  settings.skin_shrinkage = 0.0;           // the skin keeps its own size, so the shrinking ball compresses it
  settings.wrinkle.r_max_relative = 0.02;  // 0.4 mm on the 20 mm ball
  const SkinModel model = make_skin_model(sphere(), settings);
  const std::vector<Vec3> nodes = test::scaled_nodes(sphere().volume, 0.8);
  const std::vector<Vec3> t = tracking_points(model.tracking, nodes);
  // Distance of each vertex from its anchor (tracking point plus rest offset): max and mean.
  auto reach = [&](const SkinState& s) {
    double worst = 0.0, mean = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double d = (s.positions[i] - (t[i] + model.vertex_tracking_offset[i])).norm();
      worst = std::max(worst, d);
      mean += d / static_cast<double>(t.size());
    }
    return std::pair{worst, mean};
  };
  for (double moisture : {0.5 * settings.slippage.zero_below, 0.0}) {
    // Below tau_n every tracking stiffness is zero: no pull, but the skin stays within r_max of its anchors.
    SkinSimulation sim(model);
    SkinState slipped = initial_skin_state(model);
    SkinStepReport report;
    for (int s = 0; s < 60; ++s)
      report = sim.step(slipped, nodes, std::vector<double>(model.vertex_count(), moisture), dt);
    EXPECT_EQ(report.slipped, model.vertex_count());
    EXPECT_EQ(report.pulled, 0u);
    const auto [worst, mean] = reach(slipped);
    EXPECT_LE(worst, model.r_max_mm * (1.0 + 1e-6) + 1e-9) << moisture;
    // The compressed skin uses its freedom: on average it sits well away from its anchors.
    EXPECT_GT(mean, 0.3 * model.r_max_mm) << moisture;
  }
  // Wet skin is held at its anchors (r_j = 0, k_j = k_t = 1).
  SkinSimulation sim(model);
  SkinState held = initial_skin_state(model);
  SkinStepReport report;
  for (int s = 0; s < 60; ++s) report = sim.step(held, nodes, std::vector<double>(model.vertex_count(), 1.0), dt);
  EXPECT_EQ(report.slipped, 0u);
  EXPECT_LT(reach(held).second, 0.05 * model.r_max_mm);
}

TEST(SkinSimulation, ShrinkingSphereWrinklesWithoutInvertedTriangles) {
  for (double shrinkage : {0.15, 0.0}) {
    SkinSettings settings;
    settings.wrinkle = WrinkleControls::figure8(2);
    settings.skin_shrinkage = shrinkage;
    const SkinModel model = make_skin_model(sphere(), settings);
    const SkinState state = run_shrinking(model, 150, 0.8, 0.3);
    EXPECT_EQ(inverted_triangles(state, model), 0u) << "skin shrinkage " << shrinkage;
    // The skin followed the volume in (the ball's boundary nodes end at radius 8 mm, its faces inside that
    // sphere) and stays outside it.
    double mean_radius = 0.0, min_radius = INFINITY;
    for (const Vec3& p : state.positions) {
      mean_radius += p.norm();
      min_radius = std::min(min_radius, p.norm());
    }
    mean_radius /= static_cast<double>(state.positions.size());
    EXPECT_LT(mean_radius, 9.0);
    EXPECT_GT(min_radius, 0.9 * 8.0);
    // The compressed skin bends at least as much as a smooth sphere of its size (mean |H| = 1 / r).
    const WrinkleMeasure end = wrinkle_measure(state.positions, model.triangles);
    EXPECT_GT(end.mean_abs_curvature_per_mm, 0.99 / mean_radius) << "skin shrinkage " << shrinkage;
  }
}

TEST(SkinSimulation, Figure8SetsOrderTheWrinklesOfCompressedDriedSkin) {
  // The ball shrinks to 0.6 of its size while the skin dries below tau_n in the first third (and keeps its own
  // size: no skin shrinkage), so most of the shrinkage compresses slipped skin, which folds within r_max of its
  // anchors, as the flesh of the dried arm shrinks under its skin. Figure 8's sets (r_max against the edge length
  // as on the small arm, there 0.4 mm over 5 mm edges for set 0: five times the sets' relative r_max on this
  // 20 mm ball) order the wrinkles' height over the skin glued to the shrunk ball.
  constexpr int steps = 90;
  std::vector<WrinkleSize> sizes;
  for (int set = 0; set < 3; ++set) {
    SkinSettings settings;
    settings.skin_shrinkage = 0.0;
    settings.wrinkle = WrinkleControls::figure8(set);
    settings.wrinkle.r_max_relative *= 5.0;
    const SkinModel model = make_skin_model(sphere(), settings);
    SkinSimulation sim(model);
    SkinState state = initial_skin_state(model);
    std::vector<Vec3> nodes;
    for (int s = 1; s <= steps; ++s) {
      const double f = static_cast<double>(s) / steps;
      nodes = test::scaled_nodes(sphere().volume, 1.0 - 0.4 * f);
      sim.step(state, nodes, std::vector<double>(model.vertex_count(), std::max(0.05, 1.0 - 3.0 * f)), dt);
    }
    EXPECT_EQ(inverted_triangles(state, model), 0u) << "set " << set;
    std::vector<Vec3> glued = tracking_points(model.tracking, nodes);
    for (std::size_t i = 0; i < glued.size(); ++i) glued[i] += model.vertex_tracking_offset[i];
    sizes.push_back(wrinkle_size(state.positions, glued, model.triangles));
    std::printf("set %d (r_max %.3f mm): wrinkle height %.4f mm, wavelength %.2f mm (mean edge %.2f mm)\n", set,
                model.r_max_mm, sizes.back().height_mm, sizes.back().wavelength_mm, model.mean_edge_mm);
    // Folds along the skin's edges (section 9.3: "wrinkles form along triangles edges"), not a smooth lift.
    EXPECT_GT(sizes.back().wavelength_mm, 0.5 * model.mean_edge_mm) << "set " << set;
    EXPECT_LT(sizes.back().wavelength_mm, 5.0 * model.mean_edge_mm) << "set " << set;
    // No fold is higher than the slip radius allows.
    EXPECT_LT(sizes.back().height_mm, model.r_max_mm) << "set " << set;
  }
  EXPECT_GT(sizes[0].height_mm, 0.0);
  EXPECT_GT(sizes[1].height_mm, 1.3 * sizes[0].height_mm);
  EXPECT_GT(sizes[2].height_mm, 1.3 * sizes[1].height_mm);
}

TEST(SkinSimulation, SameResultAtAnyThreadCount) {
  for (DampingFrame frame : {DampingFrame::volume, DampingFrame::rigid_motion}) {
    SkinSettings settings;
    settings.damping_frame = frame;
    const SkinModel model = make_skin_model(sphere(), settings);
    set_thread_count(1);
    const SkinState one = run_shrinking(model, 40, 0.85, 0.4);
    set_thread_count(4);
    const SkinState four = run_shrinking(model, 40, 0.85, 0.4);
    set_thread_count(0);
    EXPECT_EQ(one.positions, four.positions);
    EXPECT_EQ(one.velocities, four.velocities);
    // The skin moved: the comparison is not between two rest states.
    EXPECT_GT(max_displacement(one, model), 0.5);
  }
}

TEST(SkinSimulation, ModelHasConstraintsScaledToTheModel) {
  const SkinModel model = make_skin_model(sphere());
  EXPECT_EQ(model.stretch.size(), 3 * model.triangles.size() / 2);
  EXPECT_EQ(model.bending.size(), model.stretch.size());
  EXPECT_NEAR(model.model_size_mm, 20.2, 1e-6);
  EXPECT_NEAR(model.r_max_mm, 0.002 * model.model_size_mm, 1e-12);
  EXPECT_TRUE(groups_are_independent(model.stretch_groups, model.stretch.edge_vertices, model.vertex_count()));
  EXPECT_TRUE(groups_are_independent(model.bending_groups, model.bending.quad_vertices, model.vertex_count()));
  // Equal total mass: the inverse masses are normalised to mean mass 1.
  double mass = 0.0;
  for (double w : model.vertex_inverse_mass) mass += 1.0 / w;
  EXPECT_NEAR(mass / static_cast<double>(model.vertex_count()), 1.0, 1e-9);
}

TEST(SkinSimulation, RejectsBadInput) {
  const SkinModel model = make_skin_model(sphere());
  SkinSimulation sim(model);
  SkinState state = initial_skin_state(model);
  const std::vector<double> moisture(model.vertex_count(), 1.0);
  EXPECT_THROW(sim.step(state, {Vec3::Zero()}, moisture, dt), InputError);
  EXPECT_THROW(sim.step(state, sphere().volume.positions, {1.0}, dt), InputError);
  EXPECT_THROW(sim.step(state, sphere().volume.positions, moisture, 0.0), InputError);
  SkinSettings bad;
  bad.iterations = 0;
  EXPECT_THROW(make_skin_model(sphere(), bad), InputError);
  bad = SkinSettings{};
  bad.wrinkle.damping = 1.5;
  EXPECT_THROW(make_skin_model(sphere(), bad), InputError);
  EXPECT_THROW(WrinkleControls::figure8(3), InputError);
}

TEST(SkinMoistureRatio, InterpolatesNodeMoistureAtTheTrackingPoint) {
  const BodyModel& body = sphere();
  std::vector<double> node_moisture(body.volume.vertex_count());
  // A linear field is interpolated exactly.
  for (std::size_t i = 0; i < node_moisture.size(); ++i) node_moisture[i] = 2.0 + 0.05 * body.volume.positions[i].x();
  const std::vector<double> m = skin_moisture_ratio(body.tracking, node_moisture, 4.0);
  const std::vector<Vec3> t = tracking_points(body.tracking, body.volume.positions);
  for (std::size_t i = 0; i < m.size(); ++i) EXPECT_NEAR(m[i], (2.0 + 0.05 * t[i].x()) / 4.0, 1e-12);
  EXPECT_THROW(skin_moisture_ratio(body.tracking, node_moisture, 0.0), InputError);
}
