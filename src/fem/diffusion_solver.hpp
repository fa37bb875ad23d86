#pragma once
/// Scalar diffusion with Robin (evaporation) boundaries on a tet mesh, P1 FEM with implicit Euler: the
/// moisture solver of the desiccation system (Frerichs et al. 2021, section 6, eqs. 5-16), without its
/// material laws (those live in desiccation/).
///
/// Equation solved for a field u (moisture content) on the active tets, with per-tet capacity c (eq. 5's
/// rho) and diffusivity D (eq. 5's w):
///   c du/dt = div(c D grad u)                                 in the active region        (eq. 5)
///   -c D grad u . n = cover h c (u - u_ambient)               on the Robin faces           (eq. 6)
///   -c D grad u . n = 0                                       on every other active face (insulated)
/// The mass-transfer coefficient h (m/s) multiplies the capacity of the face's tet so that for a uniform
/// c the boundary condition is the usual -D du/dn = h (u - u_ambient) (Biot number h L / D); `cover`
/// (0..1, cloth, ground) scales the evaporation per face. Discretised as (eq. 16)
///   (M + dt (K + H)) u^{n+1} = M u^n + dt f
/// with K_e = c D V grad N grad N^T (eq. 11), M_e from c (eq. 12, lumped by default), H_f and f_f from
/// cover h c (eqs. 13, 14).
///
/// Inactive tets (bone: holds no water) are left out of the system entirely: their face with the active
/// region is an insulated boundary (no flux crosses it, bone is no sink) and nodes that touch only
/// inactive tets keep their value.
///
/// Units: lengths mm (mesh positions), time s, D in m^2/s, h in m/s; u and c in the caller's units. The
/// "content" c u integrated over the volume is reported in (c units)(u units) mm^3.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/types.hpp"
#include "fem/sparse_assembly.hpp"
#include "fem/sparse_solver.hpp"
#include "geometry/tet_mesh.hpp"

namespace forensim {

/// A boundary triangle with an evaporation (Robin) condition.
struct RobinFace {
  Tri vertices{};                 ///< mesh node indices, counter-clockwise seen from outside
  Index tet = -1;                 ///< the (active) tet the face belongs to: its capacity scales h
  double transfer_m_per_s = 0.0;  ///< h_m, mass-transfer coefficient (eq. 6), m/s
  double ambient = 0.0;           ///< phi_e, equilibrium value of u in the surrounding air (eq. 6)
  double cover = 1.0;             ///< evaporation factor, 1 = bare skin, 0 = sealed (cloth, ground)
};

struct DiffusionSettings {
  bool lumped_mass = true;  ///< row-sum lumped M (monotone, no over/undershoot); false: consistent M
  /// Backend. cg_jacobi (default) is forensim's own parallel, deterministic Jacobi-preconditioned CG on the
  /// assembled matrix, warm-started from u^n and stopped by the two tests below. At hour steps M dominates
  /// M + dt (K + H) (dt D / h^2 ~ 0.02 for D = 1e-10 m^2/s on the paper arm's 4 mm tets), so it needs a
  /// handful of iterations; see bench/bench_desiccation.cpp. cholmod and cg_ic (Eigen's CG with incomplete
  /// Cholesky, relative residual cg_tolerance) remain for steps with dt D / h^2 >> 1.
  SparseSolverKind solver = SparseSolverKind::cg_jacobi;
  /// cg_jacobi: stop when every node's Jacobi correction |r_i| / A_ii (the change of u_i the residual still
  /// asks for) is below tolerance times the field's scale max |u^n|: 1e-7 of the moisture (3e-7 kg/kg at
  /// X0 = 3, where an hour's step changes the surface by about 1e-3), far below any physical or visible
  /// difference (on the paper arm 17 iterations instead of 21 at 1e-9)...
  double tolerance = 1e-7;
  /// ...and the content the residual leaves unbalanced, |sum_i r_i| (storage change + outflow, exactly),
  /// is below balance_tolerance times sum_i |b_i| (about the content): the water balance over a run of N
  /// steps then holds to N x 1e-12.
  double balance_tolerance = 1e-12;
  int max_iterations = 2000;    ///< cg_jacobi: NumericError beyond this
  double cg_tolerance = 1e-12;  ///< cg_ic: relative residual |r| / |b|
};

/// What one implicit step did. Mass balance: storage_change == -boundary_outflow up to the solver residual.
struct DiffusionStepReport {
  double boundary_outflow = 0.0;  ///< integral over the step of the Robin flux out of the domain, c u mm^3
  double storage_change = 0.0;    ///< change of the content (integral of c u) over the step, c u mm^3
  bool refactored = false;        ///< the matrix was reassembled and refactored in this step
  int iterations = 0;             ///< CG iterations (0 for the direct solver)
};

/// Tet mask (1 = takes part in diffusion) from the region labels: every tet but bone.
std::vector<std::uint8_t> diffusion_active_tets(const TetMesh& mesh);

/// The outer boundary faces of the mesh that belong to active tets (the skin, not the bone surface), all
/// with transfer coefficient `transfer_m_per_s`, `ambient` and cover 1.
std::vector<RobinFace> skin_robin_faces(const TetMesh& mesh, const std::vector<std::uint8_t>& tet_active,
                                        double transfer_m_per_s, double ambient);

class DiffusionSolver {
 public:
  /// Builds the node numbering, sparsity pattern and solver analysis once. `tet_active`: #T (empty = all
  /// tets active). `faces`: Robin faces (faces of inactive tets are ignored, they do not evaporate).
  /// Coefficients start at c = 1 and D = 1e-9 m^2/s. Throws InputError for out-of-range indices.
  DiffusionSolver(const TetMesh& mesh, std::vector<std::uint8_t> tet_active, const std::vector<RobinFace>& faces,
                  DiffusionSettings settings = {});
  ~DiffusionSolver();
  DiffusionSolver(DiffusionSolver&&) noexcept;
  DiffusionSolver& operator=(DiffusionSolver&&) noexcept;

  /// Per-tet diffusivity D (eq. 8's w), m^2/s, #T (entries of inactive tets are ignored).
  void set_tet_diffusivity(const std::vector<double>& m2_per_s);
  /// Per-tet capacity c (eq. 7's rho, any unit > 0), #T.
  void set_tet_capacity(const std::vector<double>& capacity);
  /// Per-face cover factors (0..1), one per face given to the constructor (in that order, skipped faces
  /// included).
  void set_face_cover(const std::vector<double>& cover);
  /// Per-face ambient values phi_e, one per constructor face.
  void set_face_ambient(const std::vector<double>& ambient);
  /// Current node positions, mm, #V (e.g. the shrunken body); the elements are rebuilt on the next step.
  void set_positions(const std::vector<Vec3>& positions_mm);

  /// One implicit Euler step of `dt_s` seconds (eq. 16). `values`: #V node values u, read as u^n and
  /// overwritten with u^{n+1} (nodes outside the active region are left untouched). Reassembles and
  /// refactors only when a coefficient, the geometry or dt changed since the last step.
  DiffusionStepReport step(std::vector<double>& values, double dt_s);

  /// Integral of c u over the active region (c u mm^3), the quantity whose change step() balances.
  double total_content(const std::vector<double>& values) const;

  std::size_t active_node_count() const;
  /// True when node `n` takes part in diffusion (belongs to an active tet).
  bool node_active(Index n) const;
  const SparsityPattern& pattern() const;
  /// The current system matrix M + dt (K + H) over the active nodes (valid after a step).
  const SparseMatrix& system_matrix() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// One-off use: `steps` implicit steps of `dt_s` with one diffusivity D (m^2/s) and capacity 1 on every
/// active tet (bone excluded by label). `values`: #V node values, updated in place. Returns the total
/// boundary outflow (c u mm^3).
double diffuse(const TetMesh& mesh, const std::vector<RobinFace>& faces, double diffusivity_m2_per_s, double dt_s,
               int steps, std::vector<double>& values);

}  // namespace forensim
