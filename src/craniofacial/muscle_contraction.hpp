#pragma once
/// Muscle contraction on the skin-muscle-skull spring model (skin_muscle_model.hpp; Kähler, Haber and Seidel
/// 2003, section 5: "different facial expressions can be assumed by setting muscle contractions"). An
/// activation a in [0, 1] per muscle shortens the rest length of each of its fibre segments to L (1 - c a)
/// (c: max_contraction): a linear muscle's fibres, fixed at their bony origin, pull their insertion toward
/// it; a sphincter's closed rings shrink toward their centre. The skin's static equilibrium (the minimum of
/// the model's spring energy over all free node positions) is found by one of two methods:
/// - quasi-Newton (the default): L-BFGS whose initial inverse Hessian is the inverse of the model's "global"
///   matrix of projective dynamics (Liu, Bargteil, O'Brien and Kavan 2013, "Fast simulation of mass-spring
///   systems", eq. 10; Liu, Bouaziz and Kavan 2017, "Quasi-Newton methods for real-time simulation of
///   hyperelastic materials", section 4): every spring, skull spring and attachment contributes k times its
///   node weights (c c^T), the same for x, y and z, so it is one scalar matrix (one unknown per node),
///   independent of the activations and the positions, factored once (CHOLMOD) per solve; each iteration then
///   costs one back-substitution with three columns and one gradient evaluation, with an Armijo backtracking
///   line search. The solve is restricted to the nodes near the active muscles (region_margin_mm) and the
///   region grows until the nodes held outside it are in equilibrium too;
/// - Newton with a backtracking line search (exact Hessian, projected where it is indefinite; its sparsity
///   pattern and fill-reducing ordering computed once in the constructor, each step refactors the full
///   3 #N system), kept as the reference.
/// Both stop on the same criterion: every free node's net force (the energy's gradient, on the whole model)
/// below the tolerance. Where the equilibrium is unique they agree to within it; strong contractions compress
/// the skin until it folds, the energy then has several minima, and the two methods may settle in different
/// ones (the quasi-Newton one measured as low or lower; tests/craniofacial/slow_face_expression.cpp).
/// Deterministic at any thread count: element terms are evaluated in parallel into fixed slots and summed
/// serially in a fixed order.

#include <memory>
#include <vector>

#include "craniofacial/skin_muscle_model.hpp"

namespace forensim {

class SparseSpdSolver;

enum class ContractionMethod {
  quasi_newton,  ///< L-BFGS preconditioned by the projective-dynamics matrix (fast; the default)
  newton         ///< projected Newton, one Cholesky refactorisation per step (the reference)
};

struct MuscleContractionOptions {
  double max_contraction = 0.3;  ///< c: fibre shortening at activation 1 (facial muscles shorten by about 30 %)
  ContractionMethod method = ContractionMethod::quasi_newton;
  int max_newton_iterations = 100;
  int max_quasi_newton_iterations = 3000;
  int quasi_newton_history = 8;  ///< L-BFGS memory: correction pairs kept
  /// Quasi-Newton: the solve is restricted to the free nodes within this distance (mm, along the model's
  /// springs) of an active muscle's fibres; the others are held at rest. When one of them then feels a net
  /// force above the tolerance, the margin doubles and the solve goes on, so the result meets the same
  /// criterion as a solve of the whole head. 0: the whole head from the start.
  double region_margin_mm = 30.0;
  /// Stop when every free node's net force is below max(force_tolerance, relative_force_tolerance times the
  /// largest force at the rest shape) (stiffness * mm).
  double force_tolerance = 1e-6;
  double relative_force_tolerance = 1e-3;
};

/// One equilibrium: the positions of every model node (skin first).
struct ContractionResult {
  std::vector<Vec3> node_positions;  ///< #N, mm
  int newton_iterations = 0;         ///< iterations of the method used (Newton or quasi-Newton steps)
  double max_force = 0.0;            ///< largest net force on a free node at the end
  double energy = 0.0;               ///< spring energy at the end
  double seconds = 0.0;
};

class MuscleContractionSolver {
 public:
  /// Keeps a reference to `model` (it must outlive the solver). Quasi-Newton: builds the node graph the
  /// solve region grows over; Newton: builds the Hessian pattern and its symbolic factorisation. Throws
  /// InputError for options out of range (max_contraction in (0, 1), iterations and history >= 1,
  /// tolerance > 0, region_margin_mm finite and >= 0).
  explicit MuscleContractionSolver(const SkinMuscleModel& model, const MuscleContractionOptions& options = {});
  ~MuscleContractionSolver();
  MuscleContractionSolver(const MuscleContractionSolver&) = delete;
  MuscleContractionSolver& operator=(const MuscleContractionSolver&) = delete;

  /// Equilibrium for `activations` (#M, in model.muscle_names order, each in [0, 1]; else InputError naming
  /// the muscle). All zero gives the rest positions exactly. Throws NumericError if the method does not
  /// reach the tolerance.
  ContractionResult solve(const std::vector<double>& activations) const;

  /// Spring energy and its gradient (3 #N, zero rows for fixed nodes) at `positions` for `activations`,
  /// exposed for derivative tests.
  double energy(const std::vector<Vec3>& positions, const std::vector<double>& activations,
                std::vector<double>* gradient = nullptr) const;

  const SkinMuscleModel& model() const { return m_model; }

 private:
  struct Assembly;
  struct Incidence;
  void build_newton_assembly();
  void build_incidence();
  ContractionResult solve_newton(const std::vector<double>& rest) const;
  ContractionResult solve_quasi_newton(const std::vector<double>& activations, const std::vector<double>& rest) const;
  void check_activations(const std::vector<double>& activations) const;
  std::vector<double> rest_lengths(const std::vector<double>& activations) const;

  const SkinMuscleModel& m_model;
  MuscleContractionOptions m_options;
  std::vector<Index> m_node_dof;  ///< first unknown of each node, -1 when fixed
  std::size_t m_dof_count = 0;
  std::unique_ptr<Assembly> m_assembly;    ///< Newton only
  std::unique_ptr<Incidence> m_incidence;  ///< quasi-Newton only
};

}  // namespace forensim
