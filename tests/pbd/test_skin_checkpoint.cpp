#include "pbd/skin_checkpoint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.hpp"
#include "pbd_test_models.hpp"

using namespace forensim;

namespace {

constexpr double dt = 1.0 / 30.0;

/// Steps the sphere's skin while the ball shrinks by 0.2 % and the skin dries by 1 % per step, from step `from`.
void run(SkinSimulation& sim, const BodyModel& body, SkinState& state, int from, int steps) {
  for (int s = from; s < from + steps; ++s) {
    const std::vector<Vec3> nodes = test::scaled_nodes(body.volume, 1.0 - 0.002 * s);
    sim.step(state, nodes, std::vector<double>(state.positions.size(), 1.0 - 0.01 * s), dt);
  }
}

}  // namespace

// A state read back from its checkpoint continues exactly as the original: after 10 more steps both are
// bit-identical (positions, velocities, tracking points of the last step, time, step count).
TEST(SkinCheckpoint, RestoredStateContinuesBitIdentically) {
  const BodyModel body = test::sphere_body();
  const SkinModel model = make_skin_model(body);
  SkinSimulation sim(model);
  SkinState state = initial_skin_state(model);
  run(sim, body, state, 1, 20);
  const std::string bytes = skin_state_bytes(state);
  SkinState restored = skin_state_from_bytes(bytes, model.vertex_count(), "test");
  EXPECT_EQ(skin_state_bytes(restored), bytes);
  SkinSimulation other(model);
  run(sim, body, state, 21, 10);
  run(other, body, restored, 21, 10);
  EXPECT_EQ(restored.step_count, 30);
  EXPECT_EQ(restored.time_s, state.time_s);
  ASSERT_EQ(restored.positions.size(), state.positions.size());
  for (std::size_t i = 0; i < state.positions.size(); ++i) {
    ASSERT_EQ(restored.positions[i], state.positions[i]) << i;
    ASSERT_EQ(restored.velocities[i], state.velocities[i]) << i;
    ASSERT_EQ(restored.tracking_points[i], state.tracking_points[i]) << i;
  }
  // The initial state (no tracking points yet) round-trips too.
  const SkinState fresh = initial_skin_state(model);
  const SkinState fresh_back = skin_state_from_bytes(skin_state_bytes(fresh), model.vertex_count(), "test");
  EXPECT_TRUE(fresh_back.tracking_points.empty());
  EXPECT_EQ(fresh_back.positions, fresh.positions);
}

TEST(SkinCheckpoint, RejectsMalformedBytes) {
  SkinState state;
  state.positions.assign(3, Vec3(1, 2, 3));
  state.velocities.assign(3, Vec3::Zero());
  const std::string bytes = skin_state_bytes(state);
  EXPECT_NO_THROW(skin_state_from_bytes(bytes, 3, "test"));
  EXPECT_THROW(skin_state_from_bytes(bytes, 4, "test"), InputError);                              // another skin
  EXPECT_THROW(skin_state_from_bytes(bytes.substr(0, bytes.size() - 1), 3, "test"), InputError);  // truncated
  EXPECT_THROW(skin_state_from_bytes(bytes + "x", 3, "test"), InputError);                        // trailing bytes
  EXPECT_THROW(skin_state_from_bytes("FSSKINS", 3, "test"), InputError);                          // too short
  std::string garbage = bytes;
  garbage[0] = 'X';
  EXPECT_THROW(skin_state_from_bytes(garbage, 3, "test"), InputError);
  std::string nan = bytes;
  const double bad = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan.data() + 44, &bad, sizeof bad);  // first coordinate of the first position
  try {
    skin_state_from_bytes(nan, 3, "test");
    ADD_FAILURE() << "a NaN position was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("skin vertex 0"), std::string::npos) << e.what();
  }
  state.velocities.pop_back();
  EXPECT_THROW(skin_state_bytes(state), InputError);  // sizes that do not match
}
