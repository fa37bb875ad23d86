#include "fem/corotational_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fem/tet_element.hpp"

namespace forensim {

namespace {

const std::string source = "corotational solver";
constexpr double kpa_per_pa = 1e-3;  // stress unit of (mm, kg, s): kg / (mm s^2) = 1 kPa
constexpr double kg_per_mm3_per_kg_per_m3 = 1e-9;
constexpr double internal_force_per_n = 1e3;  // force unit of (mm, kg, s): kg mm / s^2 = 1 mN

}  // namespace

ElasticMaterials elastic_materials_from_labels(const TetMesh& mesh, const ElasticMaterial& flesh,
                                               const ElasticMaterial& bone) {
  ElasticMaterials m;
  const std::size_t n = mesh.tet_count();
  // Sized at construction: resize() on an empty vector trips GCC 12's -Wnull-dereference.
  m.tet_youngs_modulus_pa = std::vector<double>(n);
  m.tet_poisson_ratio = std::vector<double>(n);
  m.tet_density_kg_per_m3 = std::vector<double>(n);
  m.tet_rigid = std::vector<std::uint8_t>(n);
  for (std::size_t t = 0; t < n; ++t) {
    const bool is_bone = mesh.label(t) == tissue_bone;
    const ElasticMaterial& mat = is_bone ? bone : flesh;
    m.tet_youngs_modulus_pa[t] = mat.youngs_modulus_pa;
    m.tet_poisson_ratio[t] = mat.poisson_ratio;
    m.tet_density_kg_per_m3[t] = mat.density_kg_per_m3;
    m.tet_rigid[t] = is_bone ? 1 : 0;
  }
  return m;
}

double shrinkage_strain(double volume_ratio) {
  if (!(volume_ratio > 0.0) || !std::isfinite(volume_ratio)) {
    throw InputError(source, "volume ratio", "must be finite and > 0, got " + std::to_string(volume_ratio));
  }
  return std::cbrt(volume_ratio) - 1.0;
}

struct CorotationalSolver::Impl {
  CorotationalSettings settings;
  std::size_t node_count = 0;
  std::vector<Tet> tets;
  std::vector<Vec3> rest;
  std::vector<Vec12> rest_corners;
  std::vector<Mat3> rest_edge_inverse;
  std::vector<Mat34> grads;
  std::vector<double> volumes;
  std::vector<Mat6> elasticity;  // internal units (kPa)
  std::vector<std::uint8_t> rigid;
  std::vector<double> shrinkage;
  std::vector<double> mass;         // kg per node
  double softest_ratio = 0.0;       // smallest trace(K_e) / trace(M_e) over the tets, 1/s^2
  std::vector<Vec3> external;       // internal force units
  std::vector<std::uint8_t> fixed;  // per node
  std::vector<Index> user_fixed;
  std::vector<Index> loose;  // nodes of no tet

  SparsityPattern pattern;
  SparseMatrix system;
  std::vector<std::ptrdiff_t> masked_entries;  // value indices zeroed for fixed dofs
  std::vector<std::ptrdiff_t> fixed_diagonals;
  std::unique_ptr<SparseSpdSolver> dynamic_solver;  // created on first use, analysed once
  std::unique_ptr<SparseSpdSolver> static_solver;

  SparseSpdSolver& get_solver(std::unique_ptr<SparseSpdSolver>& slot, SparseSolverKind kind) {
    if (!slot) {
      slot = make_sparse_solver(kind, settings.cg_tolerance);
      slot->analyse(system);
    }
    return *slot;
  }
  std::vector<Mat3> rotations;

  Mat12 stiffness(std::size_t t) const {
    const Mat6x12 b = tet_strain_matrix(grads[t]);
    const Mat12 k = volumes[t] * (b.transpose() * elasticity[t] * b);
    return 0.5 * (k + k.transpose());
  }

  Vec12 eigen_force(std::size_t t) const {
    if (rigid[t] != 0 || shrinkage[t] == 0.0) return Vec12::Zero();
    return tet_eigenstrain_force(grads[t], volumes[t], elasticity[t], shrinkage[t]);
  }

  TetCorners corners(const std::vector<Vec3>& x, std::size_t t) const {
    const Tet& tet = tets[t];
    return {x[static_cast<std::size_t>(tet[0])], x[static_cast<std::size_t>(tet[1])],
            x[static_cast<std::size_t>(tet[2])], x[static_cast<std::size_t>(tet[3])]};
  }

  void update_rotations(const std::vector<Vec3>& x) {
    rotations.resize(tets.size());
    parallel_for(0, tets.size(), [&](std::size_t t) {
      rotations[t] = rotation_from_deformation(tet_deformation_gradient(corners(x, t), rest_edge_inverse[t]));
    });
  }

  /// Elastic forces (internal units) with the current `rotations`, scattered by colour (deterministic).
  Eigen::VectorXd forces(const std::vector<Vec3>& x) const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * node_count));
    for (const auto& colour : pattern.colours()) {
      parallel_for(
          0, colour.size(),
          [&](std::size_t i) {
            const auto t = static_cast<std::size_t>(colour[i]);
            const Vec12 fe = tet_corotational_force(stiffness(t), rotations[t], stack_corners(corners(x, t)),
                                                    rest_corners[t], eigen_force(t));
            for (int a = 0; a < 4; ++a) f.segment<3>(3 * tets[t][a]) += fe.segment<3>(3 * a);
          },
          64);
    }
    for (std::size_t n = 0; n < node_count; ++n) f.segment<3>(static_cast<Eigen::Index>(3 * n)) += external[n];
    return f;
  }

  /// Total potential (internal units): elastic energy minus the work of the external forces.
  double potential(const std::vector<Vec3>& x) const {
    const double elastic = parallel_sum(0, tets.size(), [&](std::size_t t) {
      const double strain = rigid[t] != 0 ? 0.0 : shrinkage[t];
      return tet_corotational_energy(corners(x, t), rest_edge_inverse[t], volumes[t], elasticity[t], strain);
    });
    double work = 0.0;
    for (std::size_t n = 0; n < node_count; ++n) work += external[n].dot(x[n]);
    return elastic - work;
  }

  /// system = mass_scale M + stiffness_scale K' with fixed dofs replaced by identity rows and columns.
  void assemble(double mass_scale, double stiffness_scale) {
    pattern.assemble_block(
        [&](std::size_t t, Mat12& ke) { ke = stiffness_scale * rotate_stiffness(rotations[t], stiffness(t)); }, system);
    const auto& diag = pattern.diagonal_entries();
    double* values = system.valuePtr();
    for (std::size_t d = 0; d < diag.size(); ++d) values[diag[d]] += mass_scale * mass[d / 3];
    for (std::ptrdiff_t k : masked_entries) values[k] = 0.0;
    for (std::ptrdiff_t k : fixed_diagonals) values[k] = 1.0;
  }

  void update_fixed() {
    fixed.assign(node_count, 0);
    for (Index n : user_fixed) fixed[static_cast<std::size_t>(n)] = 1;
    for (Index n : loose) fixed[static_cast<std::size_t>(n)] = 1;
    if (settings.rigid_mode == RigidMode::fixed) {
      for (std::size_t t = 0; t < tets.size(); ++t) {
        if (rigid[t] != 0) {
          for (Index n : tets[t]) fixed[static_cast<std::size_t>(n)] = 1;
        }
      }
    }
    masked_entries.clear();
    fixed_diagonals.clear();
    const int* outer = system.outerIndexPtr();
    const int* inner = system.innerIndexPtr();
    for (Eigen::Index col = 0; col < system.cols(); ++col) {
      const bool col_fixed = fixed[static_cast<std::size_t>(col / 3)] != 0;
      for (int k = outer[col]; k < outer[col + 1]; ++k) {
        const bool row_fixed = fixed[static_cast<std::size_t>(inner[k] / 3)] != 0;
        if (col_fixed || row_fixed) {
          if (inner[k] == col) {
            fixed_diagonals.push_back(k);
          } else {
            masked_entries.push_back(k);
          }
        }
      }
    }
  }

  void zero_fixed(Eigen::VectorXd& v) const {
    for (std::size_t n = 0; n < node_count; ++n) {
      if (fixed[n] != 0) v.segment<3>(static_cast<Eigen::Index>(3 * n)).setZero();
    }
  }

  void check_state(const ElasticState& state) const {
    require_input(state.positions.size() == node_count, source, "state positions",
                  "wrong size " + std::to_string(state.positions.size()));
  }
};

CorotationalSolver::CorotationalSolver(const TetMesh& rest_mesh, const ElasticMaterials& materials,
                                       CorotationalSettings settings)
    : m_impl(std::make_unique<Impl>()) {
  Impl& s = *m_impl;
  s.settings = settings;
  s.node_count = rest_mesh.vertex_count();
  s.tets = rest_mesh.tets;
  s.rest = rest_mesh.positions;
  const std::size_t nt = s.tets.size();
  auto check_size = [&](std::size_t size, const char* what) {
    require_input(size == nt, source, what,
                  "has " + std::to_string(size) + " entries for " + std::to_string(nt) + " tets");
  };
  check_size(materials.tet_youngs_modulus_pa.size(), "tet_youngs_modulus_pa");
  check_size(materials.tet_poisson_ratio.size(), "tet_poisson_ratio");
  check_size(materials.tet_density_kg_per_m3.size(), "tet_density_kg_per_m3");
  s.rigid = materials.tet_rigid.empty() ? std::vector<std::uint8_t>(nt, 0) : materials.tet_rigid;
  check_size(s.rigid.size(), "tet_rigid");
  for (std::size_t t = 0; t < nt; ++t) {
    const std::string where = "tet " + std::to_string(t);
    for (Index n : s.tets[t]) {
      require_input(n >= 0 && static_cast<std::size_t>(n) < s.node_count, source, where,
                    "node index " + std::to_string(n) + " out of range");
    }
    require_input(std::isfinite(materials.tet_youngs_modulus_pa[t]) && materials.tet_youngs_modulus_pa[t] > 0.0, source,
                  where, "Young's modulus must be > 0");
    require_input(materials.tet_poisson_ratio[t] > -1.0 && materials.tet_poisson_ratio[t] < 0.5, source, where,
                  "Poisson's ratio must be in (-1, 0.5)");
    require_input(std::isfinite(materials.tet_density_kg_per_m3[t]) && materials.tet_density_kg_per_m3[t] > 0.0, source,
                  where, "density must be > 0");
  }
  s.rest_corners.resize(nt);
  s.rest_edge_inverse.resize(nt);
  s.grads.resize(nt);
  s.volumes.resize(nt);
  s.elasticity.resize(nt);
  parallel_for(0, nt, [&](std::size_t t) {
    const TetCorners p = s.corners(s.rest, t);
    s.rest_corners[t] = stack_corners(p);
    s.rest_edge_inverse[t] = tet_rest_edge_inverse(p);
    s.grads[t] = tet_shape_gradients(p, &s.volumes[t]);
    double e = materials.tet_youngs_modulus_pa[t] * kpa_per_pa;
    if (s.rigid[t] != 0 && settings.rigid_mode == RigidMode::stiff) e *= settings.rigid_stiffness_factor;
    s.elasticity[t] = isotropic_elasticity(e, materials.tet_poisson_ratio[t]);
  });
  for (std::size_t t = 0; t < nt; ++t) {
    require_input(s.volumes[t] > 0.0, source, "tet " + std::to_string(t), "is inverted (negative volume)");
  }
  // Quasi-static regularisation scale from the softest element (stiff bone must not set it).
  s.softest_ratio = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < nt; ++t) {
    const double element_mass = materials.tet_density_kg_per_m3[t] * kg_per_mm3_per_kg_per_m3 * s.volumes[t];
    s.softest_ratio = std::min(s.softest_ratio, s.stiffness(t).trace() / (3.0 * element_mass));
  }
  s.mass.assign(s.node_count, 0.0);
  for (std::size_t t = 0; t < nt; ++t) {
    const double m = materials.tet_density_kg_per_m3[t] * kg_per_mm3_per_kg_per_m3 * s.volumes[t] / 4.0;
    for (Index n : s.tets[t]) s.mass[static_cast<std::size_t>(n)] += m;
  }
  // Nodes in no tet have no mass and no stiffness: they are held in place (and given a unit mass so that
  // no zero ever reaches a diagonal).
  for (std::size_t n = 0; n < s.node_count; ++n) {
    if (s.mass[n] == 0.0) {
      s.mass[n] = 1.0;
      s.loose.push_back(static_cast<Index>(n));
    }
  }
  s.shrinkage.assign(nt, 0.0);
  s.external.assign(s.node_count, Vec3::Zero());
  s.pattern = SparsityPattern(s.tets, s.node_count, 3);
  s.system = s.pattern.make_matrix();
  s.update_fixed();
}

CorotationalSolver::~CorotationalSolver() = default;
CorotationalSolver::CorotationalSolver(CorotationalSolver&&) noexcept = default;
CorotationalSolver& CorotationalSolver::operator=(CorotationalSolver&&) noexcept = default;

ElasticState CorotationalSolver::rest_state() const {
  return ElasticState{m_impl->rest, std::vector<Vec3>(m_impl->node_count, Vec3::Zero())};
}

void CorotationalSolver::set_fixed_nodes(const std::vector<Index>& nodes) {
  for (Index n : nodes) {
    require_input(n >= 0 && static_cast<std::size_t>(n) < m_impl->node_count, source, "fixed nodes",
                  "node index " + std::to_string(n) + " out of range");
  }
  m_impl->user_fixed = nodes;
  m_impl->update_fixed();
}

void CorotationalSolver::set_tet_shrinkage_strain(const std::vector<double>& strain) {
  require_input(strain.size() == m_impl->tets.size(), source, "shrinkage strain",
                "wrong size " + std::to_string(strain.size()));
  for (std::size_t t = 0; t < strain.size(); ++t) {
    require_input(std::isfinite(strain[t]) && strain[t] > -1.0, source, "tet " + std::to_string(t),
                  "shrinkage strain must be finite and > -1");
  }
  m_impl->shrinkage = strain;
}

void CorotationalSolver::set_external_forces(const std::vector<Vec3>& forces_n) {
  if (forces_n.empty()) {
    m_impl->external.assign(m_impl->node_count, Vec3::Zero());
    return;
  }
  require_input(forces_n.size() == m_impl->node_count, source, "external forces",
                "wrong size " + std::to_string(forces_n.size()));
  for (std::size_t n = 0; n < forces_n.size(); ++n) m_impl->external[n] = forces_n[n] * internal_force_per_n;
}

void CorotationalSolver::step(ElasticState& state, double dt_s) {
  Impl& s = *m_impl;
  s.check_state(state);
  require_input(std::isfinite(dt_s) && dt_s > 0.0, source, "dt", "time step must be > 0");
  if (state.velocities.size() != s.node_count) state.velocities.assign(s.node_count, Vec3::Zero());
  s.update_rotations(state.positions);
  const double alpha = s.settings.rayleigh_alpha;
  const double beta = s.settings.rayleigh_beta;
  s.assemble(1.0 + dt_s * alpha, dt_s * beta + dt_s * dt_s);
  SparseSpdSolver& solver = s.get_solver(s.dynamic_solver, s.settings.solver);
  solver.factor(s.system);
  Eigen::VectorXd rhs = dt_s * s.forces(state.positions);
  Eigen::VectorXd v(static_cast<Eigen::Index>(3 * s.node_count));
  for (std::size_t n = 0; n < s.node_count; ++n) {
    rhs.segment<3>(static_cast<Eigen::Index>(3 * n)) += s.mass[n] * state.velocities[n];
    v.segment<3>(static_cast<Eigen::Index>(3 * n)) = state.velocities[n];
  }
  s.zero_fixed(rhs);
  solver.solve(rhs, v);
  for (std::size_t n = 0; n < s.node_count; ++n) {
    state.velocities[n] = v.segment<3>(static_cast<Eigen::Index>(3 * n));
    state.positions[n] += dt_s * state.velocities[n];
  }
}

int CorotationalSolver::solve_quasi_static(ElasticState& state) {
  Impl& s = *m_impl;
  s.check_state(state);
  state.velocities.assign(s.node_count, Vec3::Zero());
  double eps = -1.0;
  int iteration = 0;
  while (iteration < s.settings.quasi_static_max_iterations) {
    ++iteration;
    s.update_rotations(state.positions);
    if (eps < 0.0) eps = s.settings.quasi_static_regularisation * s.softest_ratio;
    s.assemble(eps, 1.0);
    SparseSpdSolver& solver = s.get_solver(s.static_solver, s.settings.quasi_static_solver);
    solver.factor(s.system);
    Eigen::VectorXd rhs = s.forces(state.positions);
    s.zero_fixed(rhs);
    Eigen::VectorXd dx = Eigen::VectorXd::Zero(rhs.size());
    solver.solve(rhs, dx);
    // Backtracking on the potential energy: the warped stiffness is not the exact tangent (it lacks the
    // derivative of R), so full steps can overshoot where shrinkage pre-stresses stiff and soft tets
    // against each other. dx is a descent direction (K' + eps M is SPD), so halving always helps.
    const double start_energy = s.potential(state.positions);
    const double slope = rhs.dot(dx);  // -dPi/dalpha at alpha = 0
    std::vector<Vec3> trial(s.node_count);
    double alpha = 1.0;
    for (int halving = 0; halving < 30; ++halving) {
      for (std::size_t n = 0; n < s.node_count; ++n) {
        trial[n] = state.positions[n] + alpha * dx.segment<3>(static_cast<Eigen::Index>(3 * n));
      }
      const double energy = s.potential(trial);
      if (energy <= start_energy - 1e-4 * alpha * slope + 1e-13 * std::abs(start_energy)) break;
      alpha *= 0.5;
    }
    double largest = 0.0;
    for (std::size_t n = 0; n < s.node_count; ++n) {
      largest = std::max(largest, (trial[n] - state.positions[n]).cwiseAbs().maxCoeff());
      state.positions[n] = trial[n];
    }
    if (!std::isfinite(largest)) throw NumericError("corotational quasi-static solve diverged");
    if (largest <= s.settings.quasi_static_tolerance_mm) break;
  }
  return iteration;
}

std::vector<Vec3> CorotationalSolver::elastic_forces(const std::vector<Vec3>& positions_mm) const {
  require_input(positions_mm.size() == m_impl->node_count, source, "positions",
                "wrong size " + std::to_string(positions_mm.size()));
  const Impl& s = *m_impl;
  std::vector<Vec3> out(s.node_count, Vec3::Zero());
  for (std::size_t t = 0; t < s.tets.size(); ++t) {
    const TetCorners p = s.corners(positions_mm, t);
    const Mat3 r = rotation_from_deformation(tet_deformation_gradient(p, s.rest_edge_inverse[t]));
    const Vec12 fe = tet_corotational_force(s.stiffness(t), r, stack_corners(p), s.rest_corners[t], s.eigen_force(t));
    for (int a = 0; a < 4; ++a) out[static_cast<std::size_t>(s.tets[t][a])] += fe.segment<3>(3 * a);
  }
  for (Vec3& f : out) f /= internal_force_per_n;
  return out;
}

double CorotationalSolver::elastic_energy(const std::vector<Vec3>& positions_mm) const {
  const Impl& s = *m_impl;
  require_input(positions_mm.size() == s.node_count, source, "positions",
                "wrong size " + std::to_string(positions_mm.size()));
  double energy = 0.0;
  for (std::size_t t = 0; t < s.tets.size(); ++t) {
    const double strain = s.rigid[t] != 0 ? 0.0 : s.shrinkage[t];
    energy += tet_corotational_energy(s.corners(positions_mm, t), s.rest_edge_inverse[t], s.volumes[t], s.elasticity[t],
                                      strain);
  }
  return energy / internal_force_per_n;  // internal energy unit kg mm^2/s^2 = mN mm
}

std::vector<double> CorotationalSolver::node_masses_kg() const {
  return m_impl->mass;
}

bool CorotationalSolver::node_fixed(Index n) const {
  return n >= 0 && static_cast<std::size_t>(n) < m_impl->node_count && m_impl->fixed[static_cast<std::size_t>(n)] != 0;
}

std::vector<Vec3> shrink_quasi_static(const TetMesh& mesh, const ElasticMaterials& materials,
                                      const std::vector<double>& tet_volume_ratio) {
  require_input(tet_volume_ratio.size() == mesh.tet_count(), source, "tet volume ratios",
                "wrong size " + std::to_string(tet_volume_ratio.size()));
  CorotationalSolver solver(mesh, materials);
  std::vector<double> strain(tet_volume_ratio.size());
  for (std::size_t t = 0; t < strain.size(); ++t) strain[t] = shrinkage_strain(tet_volume_ratio[t]);
  solver.set_tet_shrinkage_strain(strain);
  ElasticState state = solver.rest_state();
  solver.solve_quasi_static(state);
  return state.positions;
}

}  // namespace forensim
