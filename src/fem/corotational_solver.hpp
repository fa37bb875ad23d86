#pragma once
/// Corotational (element-warped) linear elasticity on a tet mesh with shrinkage eigenstrains: the volume
/// deformation of the desiccation system (Frerichs et al. 2021, section 7, eqs. 17-31; Mueller and Gross
/// 2004, "Interactive virtual materials").
///
/// Per tet e with rest corners x0_e, stiffness K_e = V B^T C B (eq. 26) and rotation R_e from the polar
/// decomposition of its deformation gradient, the elastic force is
///   f_e = -R_e (K_e (R_e^T x_e - x0_e) - V B^T C eps0_e),   eps0_e = s_e (1, 1, 1, 0, 0, 0)      (eqs. 30, 31)
/// i.e. minus the gradient of V/2 (eps - eps0):C:(eps - eps0) with eps the corotated small strain. Shrinking
/// tets add a compression barrier (tet_volume_barrier) that only acts on a tet squeezed below half of its
/// target volume: strongly drying tissue next to bone would otherwise be squeezed through zero volume.
///
/// Shrinkage: s_e is the linear eigenstrain of tet e. For a volume ratio S_v = V / V0 (eq. 28) use
/// s = S_v^(1/3) - 1 (shrinkage_strain): zero at the start, and an unconstrained body with uniform s takes
/// exactly the volume ratio (1 + s)^3 = S_v, whatever its rotation (the paper's eq. 29 writes S_v^(1/3)
/// itself, which is not zero at S_v = 1).
///
/// Dynamics (eq. 24/31): M a + D v + f_el(x) = f_ext, lumped M, Rayleigh D = alpha M + beta K', one linearised
/// implicit Euler step per call (rotations re-extracted at the start of each step):
///   ((1 + dt alpha) M + (dt beta + dt^2) K') v1 = M v0 + dt (f_el(x0) + f_ext),   x1 = x0 + dt v1.
/// Quasi-static (long steps): inexact Newton iterations x += a dx with (K' + eps M) dx = f_el(x) + f_ext
/// solved to a relative residual newton_forcing, rotations re-extracted each time and a backtracking on the
/// potential energy (a <= 1; a last step that moves no node more than the tolerance is taken whole, without
/// that energy evaluation, when it leaves every tet clear of the compression barrier); the small eps M (a proximal
/// term) makes a free body's system definite without moving the converged solution (at convergence the force vanishes).
/// A solve starts from the given shape: in a run, the previous step's, so only the change of shrinkage is left to
/// solve.
///
/// Linear solves: preconditioned CG (fem/pcg.hpp) on the warped system, applied matrix-free (per tet
/// R V B^T C B R^T, never assembled: the rotations change every iteration), preconditioned by one CHOLMOD
/// factorisation of the rest stiffness per solver (and per dt for dynamic steps), rotated by the body's
/// overall rotation (the polar rotation of the mass-weighted covariance of the current and rest positions)
/// so that a moved or turned body is preconditioned as well as one at rest. Drying bodies rotate little
/// locally, so CG needs a few iterations; the factorisation depends on the model only (never on the
/// history of a run), so a run resumed from a checkpoint repeats the same arithmetic bit for bit. Only the
/// free dofs are factorised (the fixed ones are identity rows, uncoupled): with the skeleton held, about half
/// the nodes of the paper arm and head, that cuts the factor's fill about threefold (paper arm: 20.1 to 7.0
/// million entries) and with it the cost of each preconditioner solve.
///
/// Bone ("rigid" tets) does not shrink. RigidMode::fixed holds every node of a rigid tet in place (an
/// anchored skeleton: exact, the simplest acceptable model); RigidMode::stiff multiplies the Young's
/// modulus of rigid tets by rigid_stiffness_factor instead (bone moves with the flesh, nearly undeformed).
///
/// Units: positions mm, time s, E in Pa, density kg/m^3, forces N, energies N mm. Internally mm, kg, s
/// (stress unit kPa, force unit mN).

#include <cstdint>
#include <memory>
#include <vector>

#include "core/types.hpp"
#include "fem/sparse_assembly.hpp"
#include "fem/sparse_solver.hpp"
#include "geometry/tet_mesh.hpp"

namespace forensim {

/// One isotropic linear-elastic material.
struct ElasticMaterial {
  double youngs_modulus_pa = 1e4;     ///< E
  double poisson_ratio = 0.3;         ///< nu, in (-1, 0.5)
  double density_kg_per_m3 = 1000.0;  ///< rho (eq. 25)
};

/// Per-tet materials (flat arrays, #T each).
struct ElasticMaterials {
  std::vector<double> tet_youngs_modulus_pa;
  std::vector<double> tet_poisson_ratio;
  std::vector<double> tet_density_kg_per_m3;
  std::vector<std::uint8_t> tet_rigid;  ///< 1 = bone: no shrinkage, held or stiffened (see RigidMode)
};

/// Materials from the region labels: `flesh` for every tet but bone, `bone` (rigid) for bone tets.
ElasticMaterials elastic_materials_from_labels(const TetMesh& mesh, const ElasticMaterial& flesh,
                                               const ElasticMaterial& bone);

/// Linear eigenstrain s giving the volume ratio S_v (= V / V0 > 0) when unconstrained: S_v^(1/3) - 1.
double shrinkage_strain(double volume_ratio);

enum class RigidMode {
  fixed,  ///< nodes of rigid tets do not move
  stiff,  ///< rigid tets keep their material with E * rigid_stiffness_factor
};

/// Preconditioner of the CG solves.
enum class ElasticPreconditioner {
  rest_cholesky,  ///< CHOLMOD factor of the rest stiffness (see above)
  jacobi,         ///< its diagonal: no factorisation, for meshes whose factor does not fit in memory
};

struct CorotationalSettings {
  double rayleigh_alpha = 0.0;  ///< alpha of D = alpha M + beta K, 1/s
  double rayleigh_beta = 0.0;   ///< beta, s
  RigidMode rigid_mode = RigidMode::fixed;
  double rigid_stiffness_factor = 1e3;
  int quasi_static_max_iterations = 20;
  double quasi_static_tolerance_mm = 1e-9;    ///< stop when no node moves more than this
  double quasi_static_regularisation = 1e-6;  ///< eps relative to the softest tet's trace(K_e) / trace(M_e)
  /// Relative residual of each linearised quasi-static solve (inexact Newton, Eisenstat and Walker 1996):
  /// the warped stiffness is not the exact tangent, so each Newton step cuts the error by a factor of about
  /// the strain anyway and solving it more exactly buys nothing.
  double newton_forcing = 0.05;
  /// r0 of the compression barrier (tet_volume_barrier, with kappa the tet's bulk modulus): a shrinking tet
  /// squeezed below this share of its target volume (1 + s)^3 V0 is pushed back, and none turns over. The
  /// quasi-static line search never accepts a turned-over tet. 0: no barrier.
  double volume_barrier_ratio = 0.5;
  ElasticPreconditioner preconditioner = ElasticPreconditioner::rest_cholesky;
  /// rest_cholesky: keep the factor in single precision (SparseSolverKind::cholmod_single): half the memory
  /// and memory traffic of the preconditioner solves that dominate a shape update, two subtrees of the
  /// factor solved side by side. The preconditioner stays symmetric positive definite, so CG converges to
  /// the same tolerances (the same Newton and CG counts on the paper arm). Off by default: on a loaded
  /// 2-core machine it measured no faster than CHOLMOD's own solve, and the set-up holds both factors at once.
  bool single_precision_factor = false;
  double cg_tolerance = 1e-10;  ///< dynamic step: relative residual of its CG solve
  int cg_max_iterations = 2000;
};

/// Time-varying state: #V node positions (mm) and velocities (mm/s).
struct ElasticState {
  std::vector<Vec3> positions;
  std::vector<Vec3> velocities;
};

class CorotationalSolver {
 public:
  /// Precomputes rest shapes, the 3x3-block sparsity pattern and the solver analysis. `rest_mesh` positions
  /// are the rest shape (mm). Throws InputError for wrong array sizes or invalid materials and NumericError
  /// for degenerate tets.
  CorotationalSolver(const TetMesh& rest_mesh, const ElasticMaterials& materials, CorotationalSettings settings = {});
  ~CorotationalSolver();
  CorotationalSolver(CorotationalSolver&&) noexcept;
  CorotationalSolver& operator=(CorotationalSolver&&) noexcept;

  /// The rest shape with zero velocities.
  ElasticState rest_state() const;

  /// Nodes held in place (besides the rigid tets' nodes in RigidMode::fixed); replaces earlier ones.
  void set_fixed_nodes(const std::vector<Index>& nodes);
  /// Per-tet linear shrinkage eigenstrain s (see shrinkage_strain), #T; ignored on rigid tets.
  void set_tet_shrinkage_strain(const std::vector<double>& strain);
  /// External node forces, N, #V (empty = none).
  void set_external_forces(const std::vector<Vec3>& forces_n);

  /// One implicit Euler step of dt_s seconds (eq. 31); updates positions and velocities in `state`.
  void step(ElasticState& state, double dt_s);
  /// Moves `state` to static equilibrium under the current shrinkage and external forces (velocities set
  /// to zero), starting from its positions. Returns the number of (Newton) iterations used.
  int solve_quasi_static(ElasticState& state);
  /// CG iterations of the last step() or solve_quasi_static() (summed over its Newton iterations).
  int last_cg_iterations() const;

  /// Elastic node forces f_el(x) (N) at `positions`, #V.
  std::vector<Vec3> elastic_forces(const std::vector<Vec3>& positions_mm) const;
  /// Elastic energy (N mm) at `positions`: minus the potential of elastic_forces.
  double elastic_energy(const std::vector<Vec3>& positions_mm) const;
  /// Lumped node masses, kg, #V (nodes of no tet: 1, and they are held in place).
  std::vector<double> node_masses_kg() const;
  /// True when node n is held in place.
  bool node_fixed(Index n) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// One-off use: static shape of `mesh` (rest shape) whose tets shrink to the volume ratios `tet_volume_ratio`
/// (#T, S_v each), bone per RigidMode::fixed. Returns the #V node positions, mm.
std::vector<Vec3> shrink_quasi_static(const TetMesh& mesh, const ElasticMaterials& materials,
                                      const std::vector<double>& tet_volume_ratio);

}  // namespace forensim
