#pragma once
/// The coupled desiccation run of a body model (Frerichs, Vidler and Gatzidis 2020, sections 6, 7 and 7.3):
/// moisture evaporates through the skin and diffuses inside the flesh (fem/diffusion_solver.hpp with the
/// material laws of material_laws.hpp and the boundary of environment.hpp), each tet shrinks with its
/// moisture (eq. 28) and the volume deforms (fem/corotational_solver.hpp, quasi-static for long steps).
///
/// Model (fixed: body, parameters, per-tet rest data) is apart from State (moisture, positions,
/// velocities, time). DesiccationSolver keeps the set-up-once solvers; step(state, dt) advances a State.
///
/// Moisture is dry basis (kg water / kg dry solid). Water bookkeeping is exact: the capacity of tet e is
/// rho_d0 V0_e / V_e (its dry mass per current volume), so with the lumped mass matrix the stored water
/// sum_e rho_d0 V0_e / 4 sum_corners X is unchanged by the deformation and changes only by the evaporated
/// flux (to the CG tolerance).
///
/// Calibration (defaults, arm phantom `small`, 35 C, 30 % RH, 1 m/s wind, 6 h steps): see the report of
/// bench/slow tests; the target is Papageorgopoulou et al. 2015 (a limb loses about 30 % of its mass in
/// the first two months in a hot, dry environment).

#include <filesystem>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "desiccation/environment.hpp"
#include "desiccation/material_laws.hpp"
#include "fem/corotational_solver.hpp"
#include "fem/diffusion_solver.hpp"

namespace forensim {

struct DesiccationSettings {
  TissueDrying tissue;
  TissueMaterials materials;
  DryingEnvironment environment;
  bool deform = true;        ///< solve the volume deformation (false: moisture only)
  bool quasi_static = true;  ///< quasi-static deformation per step (long steps); false: one dynamic step
  DiffusionSettings diffusion;
  /// Quasi-static solves stop when a Newton step moves no node more than 0.01 mm: 1/400 of the paper
  /// arm's mean tet edge, a tenth of a pixel of a 4k render of the whole arm; the Newton iterations
  /// contract by about 0.1 (measured on the paper arm), so the shape is within about 1e-3 mm of the
  /// equilibrium, and errors do not accumulate (each solve converges to the equilibrium of the moisture
  /// now, from the previous shape).
  CorotationalSettings elastic{.quasi_static_tolerance_mm = 1e-2};
  /// Checks every part; throws InputError naming `source`.
  void validate(const std::string& source) const;
};

/// Fixed data of a run: the body, the parameters and per-tet rest data (flat arrays, #T).
struct DesiccationModel {
  BodyModel body;
  DesiccationSettings settings;
  std::vector<double> tet_rest_volume_mm3;  ///< V0_e
  std::vector<std::uint8_t> tet_active;     ///< 1 = flesh (holds water), 0 = bone
  std::vector<RobinFace> skin_faces;        ///< evaporating boundary faces with h, X_e and cover
  double transfer_m_per_s = 0.0;            ///< h of the Robin condition (environment.hpp)
  double equilibrium_moisture = 0.0;        ///< X_e
};

/// Builds the model: validates settings and body, computes rest volumes, the skin faces (flesh boundary) with
/// h, X_e and the cover factors of the environment. Throws InputError.
DesiccationModel make_desiccation_model(BodyModel body, const DesiccationSettings& settings);

/// Time-varying data of a run.
struct DesiccationState {
  double time_s = 0.0;
  long long step_count = 0;
  std::vector<double> node_moisture;  ///< #V, X (0 on nodes that touch only bone)
  std::vector<Vec3> positions;        ///< #V, mm
  std::vector<Vec3> velocities;       ///< #V, mm/s
  double evaporated_kg = 0.0;         ///< water that left through the skin so far (time-integrated flux)
};

/// The start of a run: X0 on every flesh node, 0 on bone-only nodes, rest positions, zero velocities.
DesiccationState initial_desiccation_state(const DesiccationModel& model);

/// What one step did.
struct DesiccationStepReport {
  double evaporated_kg = 0.0;         ///< water that left through the skin during the step
  int diffusion_iterations = 0;       ///< CG iterations of the moisture step
  int deformation_iterations = 0;     ///< quasi-static (Newton) iterations (0 when not deforming)
  int deformation_cg_iterations = 0;  ///< CG iterations of the deformation, all Newton iterations together
  std::size_t inverted_tets = 0;      ///< tets with non-positive volume after the step (0 expected)
  double seconds_diffusion = 0.0, seconds_deformation = 0.0;  ///< wall time of the two parts
};

/// Water, mass and volume of a state, in total and per named part of the body.
struct DesiccationTotals {
  double water_kg = 0.0;                                              ///< water in the flesh
  double dry_kg = 0.0;                                                ///< dry solid of the flesh (constant)
  double bone_kg = 0.0;                                               ///< bone mass (constant)
  double total_kg = 0.0;                                              ///< water + dry + bone
  double volume_mm3 = 0.0;                                            ///< current volume of all tets
  std::vector<double> part_water_kg, part_total_kg, part_volume_mm3;  ///< #part_names each (may be empty)
};

/// Totals of `state` (parts from model.body.tet_parts; a tet's water is split equally among its corners'
/// moisture as in the lumped mass matrix, so parts sum to the total).
DesiccationTotals desiccation_totals(const DesiccationModel& model, const DesiccationState& state);

/// Per-tet moisture (mean of its corners; 0 for bone), #T.
std::vector<double> tet_moisture(const DesiccationModel& model, const DesiccationState& state);
/// Per-tet target volume ratio S_v from its moisture (1 for bone), #T.
std::vector<double> tet_volume_ratio(const DesiccationModel& model, const DesiccationState& state);
/// Number of tets with non-positive volume at `positions`.
std::size_t inverted_tet_count(const TetMesh& mesh, const std::vector<Vec3>& positions);

class DesiccationSolver {
 public:
  /// Sets up the diffusion and elastic solvers for `model` (kept by reference: it must outlive the solver).
  explicit DesiccationSolver(const DesiccationModel& model);
  ~DesiccationSolver();
  DesiccationSolver(DesiccationSolver&&) noexcept;
  DesiccationSolver& operator=(DesiccationSolver&&) noexcept;

  /// One step of dt_s seconds: moisture (implicit Euler with D and capacity from the current moisture and
  /// shape), then each tet's shrinkage strain from its new moisture, then the deformation. With `deform`
  /// false the shape stays as it is (quasi-static shapes depend only on the current moisture, so a caller
  /// may solve them every few steps and at output frames: the deformation costs far more than the moisture
  /// step). Throws InputError for a state of the wrong size, NumericError if the solvers fail.
  DesiccationStepReport step(DesiccationState& state, double dt_s, bool deform = true);

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// The binary checkpoint of `state` (version 1: magic, time, step count, evaporated water, #V, then the node
/// moisture, positions and velocities as float64), so a resumed run continues bit-identically.
std::string desiccation_checkpoint_bytes(const DesiccationState& state);
/// Reads back desiccation_checkpoint_bytes(); `vertex_count` is the model's #V, `source` names the bytes in
/// errors. Throws InputError for malformed or mismatched bytes (naming the byte).
DesiccationState desiccation_state_from_bytes(const std::string& bytes, std::size_t vertex_count,
                                              const std::string& source);
/// Writes `state` to a binary checkpoint file (atomically). Throws IoError.
void write_desiccation_checkpoint(const std::filesystem::path& path, const DesiccationState& state);
/// Reads a checkpoint; `vertex_count` is the model's #V. Throws InputError for a malformed or mismatched
/// file (naming the byte), IoError when it cannot be read.
DesiccationState read_desiccation_checkpoint(const std::filesystem::path& path, std::size_t vertex_count);

}  // namespace forensim
