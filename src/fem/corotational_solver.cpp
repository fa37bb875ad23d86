#include "fem/corotational_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fem/pcg.hpp"
#include "fem/tet_element.hpp"

namespace forensim {

namespace {

const std::string source = "corotational solver";
constexpr double kpa_per_pa = 1e-3;  // stress unit of (mm, kg, s): kg / (mm s^2) = 1 kPa
constexpr double kg_per_mm3_per_kg_per_m3 = 1e-9;
constexpr double internal_force_per_n = 1e3;  // force unit of (mm, kg, s): kg mm / s^2 = 1 mN
constexpr std::size_t evaluate_grain = 256;   // tets per batch of polar rotations in evaluate()

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
  std::vector<Mat34> grads;
  std::vector<double> volumes;
  std::vector<Vec2> lame;  // (lambda, mu) per tet, internal units (kPa)
  std::vector<std::uint8_t> rigid;
  std::vector<double> shrinkage;
  std::vector<double> mass;         // kg per node
  double softest_ratio = 0.0;       // smallest trace(K_e) / trace(M_e) over the tets, 1/s^2
  std::vector<Vec3> external;       // internal force units
  std::vector<std::uint8_t> fixed;  // per node
  std::vector<Index> user_fixed;
  std::vector<Index> loose;  // nodes of no tet
  std::vector<std::uint8_t> is_loose;

  // Tets with a free node (the others exert no force on free nodes), and per node the corners of those tets
  // that it is (4 t + corner, increasing): element results go to a corner buffer and nodes gather them in
  // a fixed order, so sums do not depend on the thread count.
  std::vector<Index> live_tets;
  std::vector<int> node_start, node_corners;
  mutable std::vector<Vec3> corner_buffer;
  mutable std::vector<double> tet_energy;

  SparsityPattern pattern;
  SparseMatrix system;
  std::vector<std::ptrdiff_t> masked_entries;  // value indices zeroed for fixed dofs
  std::vector<std::ptrdiff_t> fixed_diagonals;

  // Free nodes in increasing order: free node j holds dofs 3 j .. 3 j + 2 of the factorised system (fixed
  // dofs are identity rows of the full system and left out of the factor, which they would only fill).
  std::vector<Index> free_nodes;
  mutable Eigen::VectorXd free_rhs, free_solution;

  /// A factorised (or diagonal) preconditioner mass_scale M + stiffness_scale K_rest.
  struct Preconditioner {
    double mass_scale = -1.0, stiffness_scale = -1.0;
    std::unique_ptr<SparseSpdSolver> factor;
    Eigen::VectorXd inverse_diagonal;
  };
  Preconditioner static_preconditioner, dynamic_preconditioner;
  std::vector<Mat3> rotations;  // polar rotations at the last evaluate()
  Mat3 overall_rotation = Mat3::Identity();
  int cg_iterations = 0;

  Mat6 elasticity(std::size_t t) const {
    Mat6 c = Mat6::Zero();
    c.topLeftCorner<3, 3>().setConstant(lame[t][0]);
    c.topLeftCorner<3, 3>().diagonal().array() += 2.0 * lame[t][1];
    c.bottomRightCorner<3, 3>().diagonal().setConstant(lame[t][1]);
    return c;
  }

  Mat12 rest_stiffness(std::size_t t) const {
    const Mat6x12 b = tet_strain_matrix(grads[t]);
    const Mat12 k = volumes[t] * (b.transpose() * elasticity(t) * b);
    return 0.5 * (k + k.transpose());
  }

  double strain_of(std::size_t t) const { return rigid[t] != 0 ? 0.0 : shrinkage[t]; }

  /// Compression barrier energy (internal units) of tet t at deformation gradient f; adds its corner forces
  /// to `fc`. Rigid tets have none.
  double barrier(std::size_t t, const Mat3& f, Mat34& fc) const {
    if (rigid[t] != 0 || !(settings.volume_barrier_ratio > 0.0)) return 0.0;
    Mat3 gradient;
    const double psi = tet_volume_barrier(f, shrinkage[t], lame[t][0] + 2.0 * lame[t][1] / 3.0,
                                          settings.volume_barrier_ratio, &gradient);
    if (psi == 0.0) return 0.0;
    fc -= volumes[t] * gradient * grads[t];
    return volumes[t] * psi;
  }

  Mat34 corners(const Eigen::VectorXd& x, std::size_t t) const {
    Mat34 c;
    for (int a = 0; a < 4; ++a) c.col(a) = x.segment<3>(3 * static_cast<Eigen::Index>(tets[t][a]));
    return c;
  }

  /// out (3 #V) = per node the sum of its corner_buffer entries (fixed nodes: 0).
  void gather(Eigen::VectorXd& out) const {
    out.resize(static_cast<Eigen::Index>(3 * node_count));
    parallel_for_chunks(
        0, node_count,
        [&](std::size_t lo, std::size_t hi) {
          for (std::size_t n = lo; n < hi; ++n) {
            Vec3 sum = Vec3::Zero();
            if (fixed[n] == 0) {
              for (int i = node_start[n]; i < node_start[n + 1]; ++i)
                sum += corner_buffer[static_cast<std::size_t>(node_corners[static_cast<std::size_t>(i)])];
            }
            out.segment<3>(3 * static_cast<Eigen::Index>(n)) = sum;
          }
        },
        512);
  }

  /// Rotations, elastic + external forces (fixed dofs zeroed) and the potential energy (elastic energy minus
  /// the external work) at x, internal units.
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& force) {
    rotations.resize(tets.size(), Mat3::Identity());
    tet_energy.resize(live_tets.size());
    parallel_for_chunks(
        0, live_tets.size(),
        [&](std::size_t chunk_lo, std::size_t chunk_hi) {
          // Deformation gradients of up to evaluate_grain tets first, so that their polar rotations are
          // computed in batches.
          std::array<Mat3, evaluate_grain> f, r;
          f.fill(Mat3::Zero());  // (written below for the tets at hand; set for the compiler's analysis)
          for (std::size_t lo = chunk_lo; lo < chunk_hi; lo += evaluate_grain) {
            const std::size_t hi = std::min(chunk_hi, lo + evaluate_grain);
            for (std::size_t i = lo; i < hi; ++i) {
              const auto t = static_cast<std::size_t>(live_tets[i]);
              f[i - lo] = tet_field_gradient(grads[t], corners(x, t));
            }
            polar_rotations(f.data(), r.data(), hi - lo);
            for (std::size_t i = lo; i < hi; ++i) {
              const auto t = static_cast<std::size_t>(live_tets[i]);
              const Mat3& ft = f[i - lo];
              const Mat3& rt = r[i - lo];
              rotations[t] = rt;
              // corotated_stress with its strain kept for the energy e : sigma / 2.
              const Mat3 e = corotated_strain(rt, ft, strain_of(t));
              const Mat3 sigma = isotropic_stress(e, lame[t][0], lame[t][1]);
              Mat34 fc = -volumes[t] * (rt * sigma) * grads[t];
              tet_energy[i] = 0.5 * volumes[t] * (e.cwiseProduct(sigma)).sum() + barrier(t, ft, fc);
              for (int a = 0; a < 4; ++a) corner_buffer[4 * t + static_cast<std::size_t>(a)] = fc.col(a);
            }
          }
        },
        evaluate_grain);
    gather(force);
    double work = 0.0;
    for (std::size_t n = 0; n < node_count; ++n) {
      if (fixed[n] != 0) continue;
      force.segment<3>(3 * static_cast<Eigen::Index>(n)) += external[n];
      work += external[n].dot(x.segment<3>(3 * static_cast<Eigen::Index>(n)));
    }
    const double elastic = parallel_sum_chunks(0, tet_energy.size(), [&](std::size_t lo, std::size_t hi) {
      double sum = 0.0;
      for (std::size_t i = lo; i < hi; ++i) sum += tet_energy[i];
      return sum;
    });
    return elastic - work;
  }

  /// True when at x every live tet keeps a positive volume and, where the barrier acts (shrinking tets),
  /// more than volume_barrier_ratio of its target volume (where the barrier's energy and force are zero).
  bool clear_of_barrier(const Eigen::VectorXd& x) const {
    const double r0 = settings.volume_barrier_ratio > 0.0 ? settings.volume_barrier_ratio : 0.0;
    const double blocked = parallel_sum_chunks(0, live_tets.size(), [&](std::size_t lo, std::size_t hi) {
      double count = 0.0;
      for (std::size_t i = lo; i < hi; ++i) {
        const auto t = static_cast<std::size_t>(live_tets[i]);
        const double det = tet_field_gradient(grads[t], corners(x, t)).determinant();
        const double target = rigid[t] != 0 ? 0.0 : r0 * std::pow(1.0 + shrinkage[t], 3);
        if (!(det > target)) count += 1.0;
      }
      return count;
    });
    return blocked == 0.0;
  }

  /// out = mass_scale M v + stiffness_scale K'(rotations) v, identity on fixed dofs (matrix-free).
  void apply_warped(double mass_scale, double stiffness_scale, const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
    parallel_for_chunks(
        0, live_tets.size(),
        [&](std::size_t lo, std::size_t hi) {
          for (std::size_t i = lo; i < hi; ++i) {
            const auto t = static_cast<std::size_t>(live_tets[i]);
            const Mat3& r = rotations[t];
            const Mat3 sigma =
                corotated_stress(r, tet_field_gradient(grads[t], corners(v, t)), lame[t][0], lame[t][1], -1.0);
            const Mat34 fc = (stiffness_scale * volumes[t]) * (r * sigma) * grads[t];
            for (int a = 0; a < 4; ++a) corner_buffer[4 * t + static_cast<std::size_t>(a)] = fc.col(a);
          }
        },
        256);
    gather(out);
    for (std::size_t n = 0; n < node_count; ++n) {
      const auto i = 3 * static_cast<Eigen::Index>(n);
      if (fixed[n] != 0) {
        out.segment<3>(i) = v.segment<3>(i);
      } else {
        out.segment<3>(i) += (mass_scale * mass[n]) * v.segment<3>(i);
      }
    }
  }

  /// Makes `p` hold mass_scale M + stiffness_scale K_rest (fixed dofs: identity), factorised or diagonal.
  void prepare(Preconditioner& p, double mass_scale, double stiffness_scale) {
    if (p.mass_scale == mass_scale && p.stiffness_scale == stiffness_scale) return;
    if (settings.preconditioner == ElasticPreconditioner::rest_cholesky) {
      pattern.assemble_block([&](std::size_t t, Mat12& ke) { ke = stiffness_scale * rest_stiffness(t); }, system);
    } else {
      system.coeffs().setZero();
      const auto& diag = pattern.diagonal_entries();
      for (std::size_t t = 0; t < tets.size(); ++t) {
        const Mat12 k = rest_stiffness(t);
        for (int a = 0; a < 4; ++a)
          for (int c = 0; c < 3; ++c)
            system.valuePtr()[diag[static_cast<std::size_t>(3 * tets[t][a] + c)]] +=
                stiffness_scale * k(3 * a + c, 3 * a + c);
      }
    }
    const auto& diag = pattern.diagonal_entries();
    double* values = system.valuePtr();
    for (std::size_t d = 0; d < diag.size(); ++d) values[diag[d]] += mass_scale * mass[d / 3];
    for (std::ptrdiff_t k : masked_entries) values[k] = 0.0;
    for (std::ptrdiff_t k : fixed_diagonals) values[k] = 1.0;
    if (settings.preconditioner == ElasticPreconditioner::rest_cholesky && !free_nodes.empty()) {
      const SparseMatrix free_system = free_block(system);
      if (!p.factor) {
        p.factor = make_sparse_solver(settings.single_precision_factor ? SparseSolverKind::cholmod_single
                                                                       : SparseSolverKind::cholmod);
        p.factor->analyse(free_system);
      }
      p.factor->factor(free_system);
    } else if (settings.preconditioner == ElasticPreconditioner::jacobi) {
      p.inverse_diagonal.resize(static_cast<Eigen::Index>(diag.size()));
      for (std::size_t d = 0; d < diag.size(); ++d)
        p.inverse_diagonal[static_cast<Eigen::Index>(d)] = 1.0 / values[diag[d]];
    }
    p.mass_scale = mass_scale;
    p.stiffness_scale = stiffness_scale;
  }

  /// The rows and columns of the free dofs of `full` (3 #V square, full symmetric storage), in free_nodes
  /// order: the fixed dofs' rows are identity rows, uncoupled from the rest.
  SparseMatrix free_block(const SparseMatrix& full) const {
    std::vector<int> block_of(node_count, -1);
    for (std::size_t j = 0; j < free_nodes.size(); ++j)
      block_of[static_cast<std::size_t>(free_nodes[j])] = static_cast<int>(j);
    const auto size = static_cast<Eigen::Index>(3 * free_nodes.size());
    SparseMatrix out(size, size);
    const int* outer = full.outerIndexPtr();
    const int* inner = full.innerIndexPtr();
    const double* values = full.valuePtr();
    std::size_t count = 0;
    for (Index n : free_nodes)
      for (int c = 0; c < 3; ++c) {
        const auto col = 3 * static_cast<std::size_t>(n) + static_cast<std::size_t>(c);
        for (int k = outer[col]; k < outer[col + 1]; ++k)
          count += block_of[static_cast<std::size_t>(inner[k] / 3)] >= 0;
      }
    out.reserve(static_cast<Eigen::Index>(count));
    for (std::size_t j = 0; j < free_nodes.size(); ++j) {
      for (int c = 0; c < 3; ++c) {
        const auto col = 3 * static_cast<Eigen::Index>(free_nodes[j]) + c;
        out.startVec(3 * static_cast<Eigen::Index>(j) + c);
        // Rows of a column are sorted and free_nodes is increasing: the free rows stay sorted.
        for (int k = outer[col]; k < outer[col + 1]; ++k) {
          const int b = block_of[static_cast<std::size_t>(inner[k] / 3)];
          if (b >= 0) out.insertBack(3 * b + inner[k] % 3, 3 * static_cast<Eigen::Index>(j) + c) = values[k];
        }
      }
    }
    out.finalize();
    return out;
  }

  /// out = Q P^-1 Q^T r blockwise, Q the overall rotation; out = r on fixed dofs (identity rows).
  void apply_preconditioner(const Preconditioner& p, const Eigen::VectorXd& r, Eigen::VectorXd& out) const {
    if (free_nodes.empty()) {
      out = r;  // every dof fixed
      return;
    }
    if (!p.factor) {
      Eigen::VectorXd local(r.size());
      for (std::size_t n = 0; n < node_count; ++n) {
        const auto i = 3 * static_cast<Eigen::Index>(n);
        local.segment<3>(i) = overall_rotation.transpose() * r.segment<3>(i);
      }
      out = p.inverse_diagonal.cwiseProduct(local);
      for (std::size_t n = 0; n < node_count; ++n) {
        const auto i = 3 * static_cast<Eigen::Index>(n);
        out.segment<3>(i) = overall_rotation * out.segment<3>(i).eval();
      }
      return;
    }
    free_rhs.resize(static_cast<Eigen::Index>(3 * free_nodes.size()));
    for (std::size_t j = 0; j < free_nodes.size(); ++j)
      free_rhs.segment<3>(3 * static_cast<Eigen::Index>(j)) =
          overall_rotation.transpose() * r.segment<3>(3 * static_cast<Eigen::Index>(free_nodes[j]));
    p.factor->solve(free_rhs, free_solution);
    out = r;
    for (std::size_t j = 0; j < free_nodes.size(); ++j)
      out.segment<3>(3 * static_cast<Eigen::Index>(free_nodes[j])) =
          overall_rotation * free_solution.segment<3>(3 * static_cast<Eigen::Index>(j));
  }

  /// Q: polar rotation of sum_n m_n (x_n - c)(X_n - C)^T (c, C the centres of mass now and at rest).
  void update_overall_rotation(const Eigen::VectorXd& x) {
    Vec3 c = Vec3::Zero(), c0 = Vec3::Zero();
    double total = 0.0;
    for (std::size_t n = 0; n < node_count; ++n) {
      if (is_loose[n] != 0) continue;
      c += mass[n] * x.segment<3>(3 * static_cast<Eigen::Index>(n));
      c0 += mass[n] * rest[n];
      total += mass[n];
    }
    if (!(total > 0.0)) return;
    c /= total;
    c0 /= total;
    Mat3 covariance = Mat3::Zero();
    for (std::size_t n = 0; n < node_count; ++n)
      if (is_loose[n] == 0)
        covariance += mass[n] * (x.segment<3>(3 * static_cast<Eigen::Index>(n)) - c) * (rest[n] - c0).transpose();
    overall_rotation =
        covariance.allFinite() && covariance.norm() > 0.0 ? polar_rotation(covariance) : Mat3::Identity();
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
    live_tets.clear();
    for (std::size_t t = 0; t < tets.size(); ++t) {
      bool free_node = false;
      for (Index n : tets[t]) free_node = free_node || fixed[static_cast<std::size_t>(n)] == 0;
      if (free_node) live_tets.push_back(static_cast<Index>(t));
    }
    node_start.assign(node_count + 1, 0);
    for (Index t : live_tets)
      for (Index n : tets[static_cast<std::size_t>(t)]) ++node_start[static_cast<std::size_t>(n) + 1];
    for (std::size_t n = 0; n < node_count; ++n) node_start[n + 1] += node_start[n];
    node_corners.assign(static_cast<std::size_t>(node_start[node_count]), 0);
    std::vector<int> fill(node_start.begin(), node_start.end() - 1);
    for (Index t : live_tets) {
      for (int a = 0; a < 4; ++a) {
        const auto n = static_cast<std::size_t>(tets[static_cast<std::size_t>(t)][a]);
        node_corners[static_cast<std::size_t>(fill[n]++)] = 4 * t + a;
      }
    }
    free_nodes.clear();
    for (std::size_t n = 0; n < node_count; ++n)
      if (fixed[n] == 0) free_nodes.push_back(static_cast<Index>(n));
    // The preconditioners leave out (factor) or hold as identity rows (diagonal) the fixed dofs: rebuild
    // and analyse them again on next use.
    for (Preconditioner* p : {&static_preconditioner, &dynamic_preconditioner}) {
      p->mass_scale = -1.0;
      p->factor.reset();
    }
  }

  Eigen::VectorXd flatten(const std::vector<Vec3>& x) const {
    Eigen::VectorXd v(static_cast<Eigen::Index>(3 * x.size()));
    for (std::size_t n = 0; n < x.size(); ++n) v.segment<3>(3 * static_cast<Eigen::Index>(n)) = x[n];
    return v;
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
  s.grads.resize(nt);
  s.volumes.resize(nt);
  s.lame.resize(nt);
  parallel_for(0, nt, [&](std::size_t t) {
    const Tet& tet = s.tets[t];
    const TetCorners p{s.rest[static_cast<std::size_t>(tet[0])], s.rest[static_cast<std::size_t>(tet[1])],
                       s.rest[static_cast<std::size_t>(tet[2])], s.rest[static_cast<std::size_t>(tet[3])]};
    s.grads[t] = tet_shape_gradients(p, &s.volumes[t]);
    double e = materials.tet_youngs_modulus_pa[t] * kpa_per_pa;
    if (s.rigid[t] != 0 && settings.rigid_mode == RigidMode::stiff) e *= settings.rigid_stiffness_factor;
    s.lame[t] = lame_parameters(e, materials.tet_poisson_ratio[t]);
  });
  for (std::size_t t = 0; t < nt; ++t) {
    require_input(s.volumes[t] > 0.0, source, "tet " + std::to_string(t), "is inverted (negative volume)");
  }
  // Quasi-static regularisation scale from the softest element (stiff bone must not set it). For isotropic C,
  // trace(V B^T C B) = V (lambda + 4 mu) sum_a |grad N_a|^2.
  s.softest_ratio = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < nt; ++t) {
    const double element_mass = materials.tet_density_kg_per_m3[t] * kg_per_mm3_per_kg_per_m3 * s.volumes[t];
    const double trace = s.volumes[t] * (s.lame[t][0] + 4.0 * s.lame[t][1]) * s.grads[t].squaredNorm();
    s.softest_ratio = std::min(s.softest_ratio, trace / (3.0 * element_mass));
  }
  s.mass.assign(s.node_count, 0.0);
  for (std::size_t t = 0; t < nt; ++t) {
    const double m = materials.tet_density_kg_per_m3[t] * kg_per_mm3_per_kg_per_m3 * s.volumes[t] / 4.0;
    for (Index n : s.tets[t]) s.mass[static_cast<std::size_t>(n)] += m;
  }
  // Nodes in no tet have no mass and no stiffness: they are held in place (and given a unit mass so that
  // no zero ever reaches a diagonal).
  s.is_loose.assign(s.node_count, 0);
  for (std::size_t n = 0; n < s.node_count; ++n) {
    if (s.mass[n] == 0.0) {
      s.mass[n] = 1.0;
      s.loose.push_back(static_cast<Index>(n));
      s.is_loose[n] = 1;
    }
  }
  s.shrinkage.assign(nt, 0.0);
  s.external.assign(s.node_count, Vec3::Zero());
  s.corner_buffer.assign(4 * nt, Vec3::Zero());
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
    if (!(std::isfinite(strain[t]) && strain[t] > -1.0))
      throw InputError(source, "tet " + std::to_string(t), "shrinkage strain must be finite and > -1");
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
  const Eigen::VectorXd x = s.flatten(state.positions);
  Eigen::VectorXd force;
  s.evaluate(x, force);
  s.update_overall_rotation(x);
  const double mass_scale = 1.0 + dt_s * s.settings.rayleigh_alpha;
  const double stiffness_scale = dt_s * s.settings.rayleigh_beta + dt_s * dt_s;
  s.prepare(s.dynamic_preconditioner, mass_scale, stiffness_scale);
  Eigen::VectorXd v = s.flatten(state.velocities);
  Eigen::VectorXd rhs = dt_s * force;
  for (std::size_t n = 0; n < s.node_count; ++n)
    rhs.segment<3>(static_cast<Eigen::Index>(3 * n)) += s.mass[n] * state.velocities[n];
  s.zero_fixed(rhs);
  s.zero_fixed(v);
  const double limit = s.settings.cg_tolerance * std::sqrt(parallel_dot(rhs, rhs));
  const PcgResult result = preconditioned_cg(
      [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { s.apply_warped(mass_scale, stiffness_scale, in, out); },
      [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
        s.apply_preconditioner(s.dynamic_preconditioner, in, out);
      },
      rhs, v, [&](const Eigen::VectorXd& r, int) { return std::sqrt(parallel_dot(r, r)) <= limit; },
      s.settings.cg_max_iterations);
  s.cg_iterations = result.iterations;
  if (!result.converged)
    throw NumericError("corotational step: CG did not converge in " + std::to_string(result.iterations) +
                       " iterations");
  for (std::size_t n = 0; n < s.node_count; ++n) {
    state.velocities[n] = v.segment<3>(static_cast<Eigen::Index>(3 * n));
    state.positions[n] += dt_s * state.velocities[n];
  }
}

int CorotationalSolver::solve_quasi_static(ElasticState& state) {
  Impl& s = *m_impl;
  s.check_state(state);
  state.velocities.assign(s.node_count, Vec3::Zero());
  const double eps = s.settings.quasi_static_regularisation * s.softest_ratio;
  s.prepare(s.static_preconditioner, eps, 1.0);
  Eigen::VectorXd x = s.flatten(state.positions);
  s.update_overall_rotation(x);
  Eigen::VectorXd force, trial_force, trial(x.size());
  double energy = s.evaluate(x, force);  // s.rotations are those at x from here on
  if (!std::isfinite(energy))
    throw NumericError("corotational quasi-static solve: a tet of the start shape is turned over");
  s.cg_iterations = 0;
  int iteration = 0;
  while (iteration < s.settings.quasi_static_max_iterations) {
    ++iteration;
    // Inexact Newton step with the warped stiffness at x.
    Eigen::VectorXd dx = Eigen::VectorXd::Zero(x.size());
    const double limit = s.settings.newton_forcing * std::sqrt(parallel_dot(force, force));
    const PcgResult inner = preconditioned_cg(
        [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { s.apply_warped(eps, 1.0, in, out); },
        [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
          s.apply_preconditioner(s.static_preconditioner, in, out);
        },
        force, dx, [&](const Eigen::VectorXd& r, int) { return std::sqrt(parallel_dot(r, r)) <= limit; },
        s.settings.cg_max_iterations);
    s.cg_iterations += inner.iterations;
    // A last step (no node moves more than the tolerance) is taken whole without the energy evaluation of
    // the line search when it leaves every tet clear of the compression barrier (and none turned over): it
    // changes the shape by less than the tolerance, and its forces are not needed.
    if (dx.cwiseAbs().maxCoeff() <= s.settings.quasi_static_tolerance_mm) {
      trial = x + dx;
      if (s.clear_of_barrier(trial)) {
        x.swap(trial);
        break;
      }
    }
    // Backtracking on the potential energy: the warped stiffness is not the exact tangent (it lacks the
    // derivative of R), so full steps can overshoot where shrinkage pre-stresses stiff and soft tets
    // against each other. dx is a descent direction (CG on an SPD system from 0), so halving always helps.
    const double slope = parallel_dot(force, dx);  // -dPi/dalpha at alpha = 0
    // A turned-over tet has infinite energy (the compression barrier), so it is never accepted.
    double alpha = 1.0, trial_energy = energy;
    bool accepted = false;
    for (int halving = 0; halving < 30; ++halving) {
      trial = x + alpha * dx;
      trial_energy = s.evaluate(trial, trial_force);
      if (trial_energy <= energy - 1e-4 * alpha * slope + 1e-13 * std::abs(energy)) {
        accepted = true;
        break;
      }
      alpha *= 0.5;
    }
    if (!accepted && !std::isfinite(trial_energy)) {
      s.evaluate(x, force);  // no admissible step: stay (s.rotations back at x)
      break;
    }
    const double largest = alpha * dx.cwiseAbs().maxCoeff();
    x.swap(trial);
    force.swap(trial_force);  // the last evaluate() was at the accepted trial: s.rotations are at x
    energy = trial_energy;
    if (!std::isfinite(largest) || !std::isfinite(energy))
      throw NumericError("corotational quasi-static solve diverged");
    if (largest <= s.settings.quasi_static_tolerance_mm) break;
  }
  for (std::size_t n = 0; n < s.node_count; ++n) state.positions[n] = x.segment<3>(3 * static_cast<Eigen::Index>(n));
  return iteration;
}

int CorotationalSolver::last_cg_iterations() const {
  return m_impl->cg_iterations;
}

std::vector<Vec3> CorotationalSolver::elastic_forces(const std::vector<Vec3>& positions_mm) const {
  require_input(positions_mm.size() == m_impl->node_count, source, "positions",
                "wrong size " + std::to_string(positions_mm.size()));
  const Impl& s = *m_impl;
  const Eigen::VectorXd x = s.flatten(positions_mm);
  std::vector<Vec3> out(s.node_count, Vec3::Zero());
  for (std::size_t t = 0; t < s.tets.size(); ++t) {
    const Mat3 f = tet_field_gradient(s.grads[t], s.corners(x, t));
    const Mat3 r = polar_rotation(f);
    const Mat3 sigma = corotated_stress(r, f, s.lame[t][0], s.lame[t][1], s.strain_of(t));
    Mat34 fc = -s.volumes[t] * (r * sigma) * s.grads[t];
    s.barrier(t, f, fc);
    for (int a = 0; a < 4; ++a) out[static_cast<std::size_t>(s.tets[t][a])] += fc.col(a);
  }
  for (Vec3& f : out) f /= internal_force_per_n;
  return out;
}

double CorotationalSolver::elastic_energy(const std::vector<Vec3>& positions_mm) const {
  const Impl& s = *m_impl;
  require_input(positions_mm.size() == s.node_count, source, "positions",
                "wrong size " + std::to_string(positions_mm.size()));
  const Eigen::VectorXd x = s.flatten(positions_mm);
  double energy = 0.0;
  for (std::size_t t = 0; t < s.tets.size(); ++t) {
    const Mat3 f = tet_field_gradient(s.grads[t], s.corners(x, t));
    const Mat3 r = polar_rotation(f);
    const Mat3 e = corotated_strain(r, f, s.strain_of(t));
    Mat34 unused;
    energy += 0.5 * s.volumes[t] * e.cwiseProduct(isotropic_stress(e, s.lame[t][0], s.lame[t][1])).sum() +
              s.barrier(t, f, unused.setZero());
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
