#pragma once
/// How the skin of `forensim mummify` moves (Frerichs, Vidler and Gatzidis 2020, sections 8.1 and 8.2): the
/// position-based skin of src/pbd, pulled along by the shrinking volume through its tracking constraints,
/// wrinkling, slipping as it dries; or, with "pbd": false, the skin glued to the volume (each vertex at its
/// tracking point plus its rest offset).
///
/// Time stepping. The paper runs one skin step per frame of its simulation (one moisture step, one volume step,
/// one skin step). forensim solves the volume's quasi-static shape every few moisture steps (and at every
/// output frame), so the skin steps with each shape solve: `substeps` position-based steps during which the
/// volume's nodes move linearly from the previous solved shape to the new one (the skin sees a smooth motion,
/// not a jump of two days of shrinkage), all with the skin moisture of the new state. Each substep's dt is the
/// simulated time since the previous shape solve over `substeps`. With no gravity (the skin's weight does not
/// act on a drying body here) the position-based step does not depend on dt: the pull (eq. 34) is a
/// displacement divided by dt, the damping acts on v dt, so `substeps` (and the Gauss-Seidel `iterations`)
/// decide how closely the skin follows, and dt only labels the skin state's time.

#include <memory>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "core/types.hpp"
#include "desiccation/desiccation_sim.hpp"
#include "pbd/skin_simulation.hpp"

namespace forensim::cli {

/// The skin motion settings of a run (job file "skin" object: "pbd", "wrinkle", "iterations", "substeps",
/// "bending_interval", "skin_shrinkage", "slippage").
struct SkinMotionJob {
  bool pbd = true;        ///< false: the skin follows the volume rigidly (tracking point + rest offset)
  int substeps = 8;       ///< position-based steps per shape solve of the volume
  SkinSettings settings;  ///< wrinkle controls, iterations, slippage thresholds, stiffness (gravity stays 0)
  int wrinkle_set = 1;    ///< Figure 8 set the wrinkle controls came from, or -1 when given as numbers
};

/// What one advance() did (sums over its substeps).
struct SkinMotionReport {
  int steps = 0;
  std::size_t pulled = 0, slipped = 0, collisions = 0;  ///< of the last substep
  double max_tracking_excess_mm = 0.0;                  ///< of the last substep
  double seconds = 0.0;
};

/// The skin's motion through a run: owns the skin model (constraints, colouring, tracking, collision candidates),
/// its solver and its state. Output does not depend on the thread count.
class MummifySkinMotion {
 public:
  /// `body` is kept by reference (it must outlive this object); `initial_moisture` is phi_0 of the flesh.
  /// Throws InputError for bad settings.
  MummifySkinMotion(const BodyModel& body, double initial_moisture, const SkinMotionJob& job);
  ~MummifySkinMotion();

  /// Moves the skin from the volume at `from_nodes` (#V, the shape at the previous call, or the rest volume at
  /// the first) to the volume and moisture of `state` (its time the end of the motion). Throws InputError for
  /// sizes that do not match the body, NumericError when the skin blows up.
  SkinMotionReport advance(const std::vector<Vec3>& from_nodes, const DesiccationState& state);

  /// Current skin vertex positions (#S, mm).
  const std::vector<Vec3>& positions() const { return m_positions; }
  bool pbd() const { return m_job.pbd; }
  /// Position-based steps taken so far (restored with a checkpoint; 0 for the glued skin).
  long long step_count() const { return m_state.step_count; }
  /// The skin model (pbd only; throws InputError otherwise).
  const SkinModel& model() const;

  /// Checkpoint of the motion (the skin state and the time of the last advance; empty for the rigid skin, which
  /// has no state of its own).
  std::string checkpoint_bytes() const;
  /// Restores a checkpoint_bytes() (with the desiccation state it was saved with, whose node positions are
  /// the shape of the last advance). Throws InputError naming `source` for bytes that do not fit.
  void restore(const std::string& bytes, const DesiccationState& state, const std::string& source);

 private:
  const BodyModel& m_body;
  double m_initial_moisture = 1.0;
  SkinMotionJob m_job;
  std::vector<Vec3> m_rest_offsets, m_positions;
  std::unique_ptr<SkinModel> m_model;
  std::unique_ptr<SkinSimulation> m_sim;
  SkinState m_state;
  double m_time_s = 0.0;  ///< simulated time of the last advance
  std::vector<Vec3> m_nodes;
  std::vector<double> m_moisture;
};

}  // namespace forensim::cli
