#include "craniofacial/muscle_contraction.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "craniofacial/skin_spring_kernels.hpp"
#include "fem/sparse_solver.hpp"

namespace forensim {

/// The Hessian's fixed structure: every term writes its entries into fixed slots; slot_value_index maps each
/// slot to its entry of the compressed matrix (-1 where a fixed node is involved).
struct MuscleContractionSolver::Assembly {
  std::size_t spring_slots = 0, skull_slots = 0, attachment_slots = 0;
  std::vector<Index> slot_value_index;
  SparseMatrix matrix;
  std::unique_ptr<SparseSpdSolver> solver;
};

/// Which terms touch which nodes, and the nodes' neighbours with their rest distances (mm): the graph over
/// which the quasi-Newton solve's region grows.
struct MuscleContractionSolver::Incidence {
  std::vector<std::size_t> node_term_offsets;  ///< #N + 1
  std::vector<std::size_t> node_terms;         ///< springs s (s < #springs), then attachments #springs + k
  std::vector<std::size_t> node_neighbour_offsets;
  std::vector<Index> node_neighbours;
  std::vector<double> node_neighbour_mm;
};

namespace {

constexpr std::size_t spring_slot_count = 36;      // 6 x 6
constexpr std::size_t attachment_slot_count = 48;  // 4 x 4 node pairs, diagonal of each 3 x 3 block

/// Per-term results of one evaluation.
struct Terms {
  std::vector<double> spring_energy;
  std::vector<Vec6> spring_gradient;
  std::vector<Vec3> attachment_residual;
  std::vector<double> slot_values;
};

}  // namespace

MuscleContractionSolver::MuscleContractionSolver(const SkinMuscleModel& model, const MuscleContractionOptions& options)
    : m_model(model), m_options(options) {
  require_input(
      std::isfinite(options.max_contraction) && options.max_contraction > 0.0 && options.max_contraction < 1.0,
      "muscle contraction options", "max_contraction",
      "must be in (0, 1), got " + std::to_string(options.max_contraction));
  require_input(options.max_newton_iterations >= 1, "muscle contraction options", "max_newton_iterations",
                "must be at least 1");
  require_input(std::isfinite(options.force_tolerance) && options.force_tolerance > 0.0, "muscle contraction options",
                "force_tolerance", "must be positive");
  require_input(std::isfinite(options.relative_force_tolerance) && options.relative_force_tolerance >= 0.0 &&
                    options.relative_force_tolerance < 1.0,
                "muscle contraction options", "relative_force_tolerance", "must be in [0, 1)");
  const std::size_t n = model.node_rest_positions.size();
  m_node_dof.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (!model.node_fixed[i]) {
      m_node_dof[i] = static_cast<Index>(m_dof_count);
      m_dof_count += 3;
    }
  }
  require_input(options.max_quasi_newton_iterations >= 1, "muscle contraction options", "max_quasi_newton_iterations",
                "must be at least 1");
  require_input(options.quasi_newton_history >= 1, "muscle contraction options", "quasi_newton_history",
                "must be at least 1");
  require_input(std::isfinite(options.region_margin_mm) && options.region_margin_mm >= 0.0,
                "muscle contraction options", "region_margin_mm",
                "must be finite and >= 0, got " + std::to_string(options.region_margin_mm));
  if (options.method == ContractionMethod::newton) {
    build_newton_assembly();
  } else {
    build_incidence();
  }
}

void MuscleContractionSolver::build_incidence() {
  const SkinMuscleModel& model = m_model;
  const std::size_t n = model.node_rest_positions.size(), ns = model.spring_nodes.size();
  m_incidence = std::make_unique<Incidence>();
  Incidence& inc = *m_incidence;
  std::vector<std::vector<std::size_t>> terms(n);
  std::vector<std::vector<std::pair<Index, double>>> neighbours(n);
  auto link = [&](Index a, Index b) {
    const double mm = (model.node_rest_positions[static_cast<std::size_t>(a)] -
                       model.node_rest_positions[static_cast<std::size_t>(b)])
                          .norm();
    neighbours[static_cast<std::size_t>(a)].emplace_back(b, mm);
    neighbours[static_cast<std::size_t>(b)].emplace_back(a, mm);
  };
  for (std::size_t s = 0; s < ns; ++s) {
    const auto& e = model.spring_nodes[s];
    terms[static_cast<std::size_t>(e[0])].push_back(s);
    terms[static_cast<std::size_t>(e[1])].push_back(s);
    link(e[0], e[1]);
  }
  for (std::size_t k = 0; k < model.attachment_node.size(); ++k) {
    const Tri& t = model.attachment_triangle[k];
    for (Index c : {t[0], t[1], t[2], model.attachment_node[k]}) terms[static_cast<std::size_t>(c)].push_back(ns + k);
    for (Index c : {t[0], t[1], t[2]}) link(c, model.attachment_node[k]);
  }
  inc.node_term_offsets.assign(1, 0);
  inc.node_neighbour_offsets.assign(1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    inc.node_terms.insert(inc.node_terms.end(), terms[i].begin(), terms[i].end());
    inc.node_term_offsets.push_back(inc.node_terms.size());
    for (const auto& [j, mm] : neighbours[i]) {
      inc.node_neighbours.push_back(j);
      inc.node_neighbour_mm.push_back(mm);
    }
    inc.node_neighbour_offsets.push_back(inc.node_neighbours.size());
  }
}

void MuscleContractionSolver::build_newton_assembly() {
  const SkinMuscleModel& model = m_model;
  m_assembly = std::make_unique<Assembly>();
  Assembly& a = *m_assembly;
  a.spring_slots = model.spring_nodes.size() * spring_slot_count;
  a.skull_slots = model.skin_node_count * 3;
  a.attachment_slots = model.attachment_node.size() * attachment_slot_count;
  const std::size_t slots = a.spring_slots + a.skull_slots + a.attachment_slots;
  std::vector<std::pair<Index, Index>> slot_entry(slots, {-1, -1});
  auto pair_entries = [&](std::size_t first_slot, Index na, Index nb, bool full) {
    const Index da = m_node_dof[static_cast<std::size_t>(na)], db = m_node_dof[static_cast<std::size_t>(nb)];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        if (!full && r != c) continue;
        const std::size_t slot =
            first_slot + (full ? static_cast<std::size_t>(3 * r + c) : static_cast<std::size_t>(r));
        if (da >= 0 && db >= 0) slot_entry[slot] = {da + r, db + c};
      }
    }
  };
  for (std::size_t s = 0; s < model.spring_nodes.size(); ++s) {
    const auto& e = model.spring_nodes[s];
    for (int p = 0; p < 2; ++p) {
      for (int q = 0; q < 2; ++q) {
        pair_entries(s * spring_slot_count + static_cast<std::size_t>(9 * (2 * p + q)), e[static_cast<std::size_t>(p)],
                     e[static_cast<std::size_t>(q)], true);
      }
    }
  }
  for (std::size_t i = 0; i < model.skin_node_count; ++i) {
    pair_entries(a.spring_slots + 3 * i, static_cast<Index>(i), static_cast<Index>(i), false);
  }
  for (std::size_t k = 0; k < model.attachment_node.size(); ++k) {
    const Tri& t = model.attachment_triangle[k];
    const std::array<Index, 4> nodes = {t[0], t[1], t[2], model.attachment_node[k]};
    for (int p = 0; p < 4; ++p) {
      for (int q = 0; q < 4; ++q) {
        pair_entries(
            a.spring_slots + a.skull_slots + k * attachment_slot_count + static_cast<std::size_t>(3 * (4 * p + q)),
            nodes[static_cast<std::size_t>(p)], nodes[static_cast<std::size_t>(q)], false);
      }
    }
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(slots);
  for (const auto& [r, c] : slot_entry) {
    if (r >= 0) triplets.emplace_back(r, c, 1.0);
  }
  a.matrix.resize(static_cast<Eigen::Index>(m_dof_count), static_cast<Eigen::Index>(m_dof_count));
  a.matrix.setFromTriplets(triplets.begin(), triplets.end());
  a.matrix.makeCompressed();
  a.slot_value_index.assign(slots, -1);
  const int* outer = a.matrix.outerIndexPtr();
  const int* inner = a.matrix.innerIndexPtr();
  for (std::size_t s = 0; s < slots; ++s) {
    const auto [r, c] = slot_entry[s];
    if (r < 0) continue;
    const int* begin = inner + outer[c];
    const int* end = inner + outer[c + 1];
    const int* it = std::lower_bound(begin, end, r);
    a.slot_value_index[s] = static_cast<Index>(it - inner);
  }
  a.solver = make_sparse_solver(SparseSolverKind::cholmod);
  a.solver->analyse(a.matrix);
}

MuscleContractionSolver::~MuscleContractionSolver() = default;

void MuscleContractionSolver::check_activations(const std::vector<double>& activations) const {
  require_input(activations.size() == m_model.muscle_names.size(), "muscle activations", "",
                "expected " + std::to_string(m_model.muscle_names.size()) + " values (one per muscle), got " +
                    std::to_string(activations.size()));
  for (std::size_t k = 0; k < activations.size(); ++k) {
    require_input(std::isfinite(activations[k]) && activations[k] >= 0.0 && activations[k] <= 1.0, "muscle activations",
                  m_model.muscle_names[k], "must be in [0, 1], got " + std::to_string(activations[k]));
  }
}

std::vector<double> MuscleContractionSolver::rest_lengths(const std::vector<double>& activations) const {
  std::vector<double> rest = m_model.spring_rest_length_mm;
  for (std::size_t s = 0; s < rest.size(); ++s) {
    const Index k = m_model.spring_muscle[s];
    if (k >= 0) rest[s] *= 1.0 - m_options.max_contraction * activations[static_cast<std::size_t>(k)];
  }
  return rest;
}

namespace {

/// Evaluates every term at `x` in parallel, each into its own slots.
/// `project`: clamp the springs' Hessians to positive semi-definite (spring_term()).
void evaluate_terms(const SkinMuscleModel& m, const std::vector<Vec3>& x, const std::vector<double>& rest, bool hessian,
                    bool project, std::size_t spring_slots, std::size_t skull_slots, Terms& t) {
  const std::size_t ns = m.spring_nodes.size(), na = m.attachment_node.size();
  t.spring_energy.resize(ns);
  t.spring_gradient.resize(ns);
  t.attachment_residual.resize(na);
  if (hessian) t.slot_values.assign(spring_slots + skull_slots + na * attachment_slot_count, 0.0);
  parallel_for(0, ns, [&](std::size_t s) {
    const auto& e = m.spring_nodes[s];
    const bool tension_only = false;  // see SkinMuscleModel: a kink at the rest length stalls Newton
    const SpringTerm term = spring_term(x[static_cast<std::size_t>(e[0])], x[static_cast<std::size_t>(e[1])], rest[s],
                                        m.spring_stiffness[s], tension_only, project);
    t.spring_energy[s] = term.energy;
    t.spring_gradient[s] = term.gradient;
    if (!hessian) return;
    double* out = t.slot_values.data() + s * spring_slot_count;
    for (int p = 0; p < 2; ++p) {
      for (int q = 0; q < 2; ++q) {
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) out[9 * (2 * p + q) + 3 * r + c] = term.hessian(3 * p + r, 3 * q + c);
        }
      }
    }
  });
  parallel_for(0, na, [&](std::size_t k) {
    const Tri& tri = m.attachment_triangle[k];
    t.attachment_residual[k] = attachment_residual(
        x[static_cast<std::size_t>(tri[0])], x[static_cast<std::size_t>(tri[1])], x[static_cast<std::size_t>(tri[2])],
        x[static_cast<std::size_t>(m.attachment_node[k])], m.attachment_barycentric[k], m.attachment_offset[k]);
    if (!hessian) return;
    const Vec3& w = m.attachment_barycentric[k];
    const double c[4] = {w(0), w(1), w(2), -1.0};
    double* out = t.slot_values.data() + spring_slots + skull_slots + k * attachment_slot_count;
    for (int p = 0; p < 4; ++p) {
      for (int q = 0; q < 4; ++q) {
        for (int r = 0; r < 3; ++r) out[3 * (4 * p + q) + r] = m.attachment_stiffness * c[p] * c[q];
      }
    }
  });
  if (hessian) {
    for (std::size_t i = 0; i < m.skin_node_count; ++i) {
      for (int r = 0; r < 3; ++r)
        t.slot_values[spring_slots + 3 * i + static_cast<std::size_t>(r)] = m.node_skull_stiffness[i];
    }
  }
}

/// Serial, fixed-order sums of the terms: energy and gradient (3 #N).
double reduce_terms(const SkinMuscleModel& m, const std::vector<Vec3>& x, const Terms& t, std::vector<double>& g) {
  g.assign(3 * x.size(), 0.0);
  double energy = 0.0;
  for (std::size_t s = 0; s < m.spring_nodes.size(); ++s) {
    energy += t.spring_energy[s];
    for (int p = 0; p < 2; ++p) {
      const std::size_t n = static_cast<std::size_t>(m.spring_nodes[s][static_cast<std::size_t>(p)]);
      for (int r = 0; r < 3; ++r) g[3 * n + static_cast<std::size_t>(r)] += t.spring_gradient[s](3 * p + r);
    }
  }
  for (std::size_t i = 0; i < m.skin_node_count; ++i) {
    const Vec3 d = x[i] - m.node_rest_positions[i];
    energy += 0.5 * m.node_skull_stiffness[i] * d.squaredNorm();
    for (int r = 0; r < 3; ++r) g[3 * i + static_cast<std::size_t>(r)] += m.node_skull_stiffness[i] * d(r);
  }
  for (std::size_t k = 0; k < m.attachment_node.size(); ++k) {
    const Vec3& res = t.attachment_residual[k];
    energy += 0.5 * m.attachment_stiffness * res.squaredNorm();
    const Tri& tri = m.attachment_triangle[k];
    const Vec3& w = m.attachment_barycentric[k];
    const std::size_t nodes[4] = {static_cast<std::size_t>(tri[0]), static_cast<std::size_t>(tri[1]),
                                  static_cast<std::size_t>(tri[2]), static_cast<std::size_t>(m.attachment_node[k])};
    const double c[4] = {w(0), w(1), w(2), -1.0};
    for (int p = 0; p < 4; ++p) {
      for (int r = 0; r < 3; ++r)
        g[3 * nodes[p] + static_cast<std::size_t>(r)] += m.attachment_stiffness * c[p] * res(r);
    }
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (m.node_fixed[i]) g[3 * i] = g[3 * i + 1] = g[3 * i + 2] = 0.0;
  }
  return energy;
}

/// Per-term forces of one quasi-Newton evaluation.
struct Forces {
  std::vector<SpringForce> spring;
  std::vector<Vec3> attachment_residual;
};

/// The terms a quasi-Newton evaluation sums (all, or those touching the region's nodes), ascending.
struct TermSet {
  std::vector<std::size_t> springs, attachments, skin_nodes;
};

/// Energy and gradient (on the DOFs of `node_dof`: 3 per node, -1 for nodes held in place) of the terms of
/// `set` at `x`: terms in parallel into their slots, then summed serially in a fixed order.
double evaluate_forces(const SkinMuscleModel& m, const std::vector<Index>& node_dof, const std::vector<Vec3>& x,
                       const std::vector<double>& rest, const TermSet& set, Forces& f, Eigen::VectorXd& gradient) {
  const std::size_t ns = set.springs.size(), na = set.attachments.size();
  f.spring.resize(ns);
  f.attachment_residual.resize(na);
  parallel_for_chunks(0, ns, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t j = lo; j < hi; ++j) {
      const std::size_t s = set.springs[j];
      const auto& e = m.spring_nodes[s];
      f.spring[j] = spring_force(x[static_cast<std::size_t>(e[0])], x[static_cast<std::size_t>(e[1])], rest[s],
                                 m.spring_stiffness[s]);
    }
  });
  parallel_for_chunks(0, na, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t j = lo; j < hi; ++j) {
      const std::size_t k = set.attachments[j];
      const Tri& tri = m.attachment_triangle[k];
      f.attachment_residual[j] = attachment_residual(
          x[static_cast<std::size_t>(tri[0])], x[static_cast<std::size_t>(tri[1])], x[static_cast<std::size_t>(tri[2])],
          x[static_cast<std::size_t>(m.attachment_node[k])], m.attachment_barycentric[k], m.attachment_offset[k]);
    }
  });
  gradient.setZero();
  auto add = [&](Index node, const Vec3& v) {
    const Index d = node_dof[static_cast<std::size_t>(node)];
    if (d >= 0) gradient.segment<3>(d) += v;
  };
  double energy = 0.0;
  for (std::size_t j = 0; j < ns; ++j) {
    const auto& e = m.spring_nodes[set.springs[j]];
    energy += f.spring[j].energy;
    add(e[0], f.spring[j].gradient_a);
    add(e[1], -f.spring[j].gradient_a);
  }
  for (std::size_t i : set.skin_nodes) {
    const Vec3 d = x[i] - m.node_rest_positions[i];
    energy += 0.5 * m.node_skull_stiffness[i] * d.squaredNorm();
    add(static_cast<Index>(i), m.node_skull_stiffness[i] * d);
  }
  for (std::size_t j = 0; j < na; ++j) {
    const std::size_t k = set.attachments[j];
    const Vec3& r = f.attachment_residual[j];
    energy += 0.5 * m.attachment_stiffness * r.squaredNorm();
    const Tri& tri = m.attachment_triangle[k];
    const Vec3& w = m.attachment_barycentric[k];
    const Vec3 kr = m.attachment_stiffness * r;
    add(tri[0], w(0) * kr);
    add(tri[1], w(1) * kr);
    add(tri[2], w(2) * kr);
    add(m.attachment_node[k], -kr);
  }
  return energy;
}

/// The projective-dynamics matrix (Liu et al. 2013, eq. 10) on the nodes of `node_dof` (scalar unknown d / 3):
/// k c c^T of every term of `set` over its nodes' weights c, entries of held nodes dropped.
SparseMatrix global_matrix(const SkinMuscleModel& m, const std::vector<Index>& node_dof, const TermSet& set,
                           Eigen::Index unknowns) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(4 * set.springs.size() + set.skin_nodes.size() + 16 * set.attachments.size());
  auto add = [&](Index a, Index b, double value) {
    const Index da = node_dof[static_cast<std::size_t>(a)], db = node_dof[static_cast<std::size_t>(b)];
    if (da >= 0 && db >= 0) triplets.emplace_back(da / 3, db / 3, value);
  };
  for (std::size_t s : set.springs) {
    const auto& e = m.spring_nodes[s];
    const double k = m.spring_stiffness[s];
    add(e[0], e[0], k);
    add(e[1], e[1], k);
    add(e[0], e[1], -k);
    add(e[1], e[0], -k);
  }
  for (std::size_t i : set.skin_nodes) add(static_cast<Index>(i), static_cast<Index>(i), m.node_skull_stiffness[i]);
  for (std::size_t k : set.attachments) {
    const Tri& t = m.attachment_triangle[k];
    const Vec3& w = m.attachment_barycentric[k];
    const std::array<Index, 4> nodes = {t[0], t[1], t[2], m.attachment_node[k]};
    const double c[4] = {w(0), w(1), w(2), -1.0};
    for (int p = 0; p < 4; ++p) {
      for (int q = 0; q < 4; ++q) {
        add(nodes[static_cast<std::size_t>(p)], nodes[static_cast<std::size_t>(q)],
            m.attachment_stiffness * c[p] * c[q]);
      }
    }
  }
  SparseMatrix matrix(unknowns, unknowns);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  matrix.makeCompressed();
  return matrix;
}

}  // namespace

double MuscleContractionSolver::energy(const std::vector<Vec3>& positions, const std::vector<double>& activations,
                                       std::vector<double>* gradient) const {
  check_activations(activations);
  require_input(positions.size() == m_model.node_rest_positions.size(), "muscle contraction positions", "",
                "expected one position per model node");
  Terms t;
  evaluate_terms(m_model, positions, rest_lengths(activations), false, true, 0, 0, t);
  std::vector<double> g;
  const double e = reduce_terms(m_model, positions, t, g);
  if (gradient) *gradient = std::move(g);
  return e;
}

ContractionResult MuscleContractionSolver::solve(const std::vector<double>& activations) const {
  const auto start = std::chrono::steady_clock::now();
  check_activations(activations);
  const std::vector<double> rest = rest_lengths(activations);
  ContractionResult out =
      m_options.method == ContractionMethod::newton ? solve_newton(rest) : solve_quasi_newton(activations, rest);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

ContractionResult MuscleContractionSolver::solve_newton(const std::vector<double>& rest) const {
  Assembly& a = *m_assembly;
  ContractionResult out;
  std::vector<Vec3> x = m_model.node_rest_positions;
  Terms t;
  std::vector<double> g;
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(m_dof_count)), step;
  auto max_force = [&](const std::vector<double>& grad) {
    double f = 0.0;
    for (double v : grad) f = std::max(f, std::abs(v));
    return f;
  };
  evaluate_terms(m_model, x, rest, true, false, a.spring_slots, a.skull_slots, t);
  double energy = reduce_terms(m_model, x, t, g);
  double force = max_force(g);
  const double tolerance = std::max(m_options.force_tolerance, m_options.relative_force_tolerance * force);
  int iteration = 0;
  for (; iteration < m_options.max_newton_iterations && force > tolerance; ++iteration) {
    auto scatter = [&](const Terms& terms) {
      double* values = a.matrix.valuePtr();
      std::fill(values, values + a.matrix.nonZeros(), 0.0);
      for (std::size_t s = 0; s < a.slot_value_index.size(); ++s) {
        if (a.slot_value_index[s] >= 0) values[a.slot_value_index[s]] += terms.slot_values[s];
      }
    };
    scatter(t);
    for (std::size_t i = 0; i < x.size(); ++i) {
      const Index d = m_node_dof[i];
      if (d < 0) continue;
      for (int r = 0; r < 3; ++r) rhs(d + r) = -g[3 * i + static_cast<std::size_t>(r)];
    }
    // The exact Hessian converges quadratically where it is positive definite; where compressed springs make
    // it indefinite, fall back to the projected one (transverse factors clamped at 0).
    try {
      a.solver->factor(a.matrix);
    } catch (const NumericError&) {
      Terms projected;
      evaluate_terms(m_model, x, rest, true, true, a.spring_slots, a.skull_slots, projected);
      scatter(projected);
      a.solver->factor(a.matrix);
    }
    step.setZero(rhs.size());
    a.solver->solve(rhs, step);
    const double slope = -rhs.dot(step);
    // Backtracking (Armijo) line search on the energy.
    double alpha = 1.0;
    std::vector<Vec3> trial(x.size());
    double trial_energy = energy;
    std::vector<double> trial_g;
    Terms trial_terms;
    bool accepted = false;
    for (int ls = 0; ls < 40; ++ls) {
      for (std::size_t i = 0; i < x.size(); ++i) {
        const Index d = m_node_dof[i];
        trial[i] = d < 0 ? x[i] : Vec3(x[i] + alpha * step.segment<3>(d));
      }
      evaluate_terms(m_model, trial, rest, true, false, a.spring_slots, a.skull_slots, trial_terms);
      trial_energy = reduce_terms(m_model, trial, trial_terms, trial_g);
      if (trial_energy <= energy + 1e-4 * alpha * slope || max_force(trial_g) < force * 1e-3) {
        accepted = true;
        break;
      }
      alpha *= 0.5;
    }
    if (!accepted) break;
    x.swap(trial);
    std::swap(t, trial_terms);
    g.swap(trial_g);
    energy = trial_energy;
    force = max_force(g);
  }
  if (!(force <= tolerance)) {
    throw NumericError("muscle contraction: Newton stopped after " + std::to_string(iteration) +
                       " iterations with net force " + std::to_string(force) + " (tolerance " +
                       std::to_string(tolerance) + ")");
  }
  out.node_positions = std::move(x);
  out.newton_iterations = iteration;
  out.max_force = force;
  out.energy = energy;
  return out;
}

ContractionResult MuscleContractionSolver::solve_quasi_newton(const std::vector<double>& activations,
                                                              const std::vector<double>& rest) const {
  const SkinMuscleModel& m = m_model;
  const Incidence& inc = *m_incidence;
  const std::size_t nodes = m.node_rest_positions.size(), ns = m.spring_nodes.size();
  auto max_abs = [](const Eigen::VectorXd& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); };
  Forces forces;

  // The whole model: the tolerance from the force at the rest shape, and the final check.
  TermSet all;
  all.springs.resize(ns);
  all.attachments.resize(m.attachment_node.size());
  all.skin_nodes.resize(m.skin_node_count);
  for (std::size_t j = 0; j < ns; ++j) all.springs[j] = j;
  for (std::size_t j = 0; j < all.attachments.size(); ++j) all.attachments[j] = j;
  for (std::size_t j = 0; j < m.skin_node_count; ++j) all.skin_nodes[j] = j;
  std::vector<Vec3> x = m.node_rest_positions, trial;
  Eigen::VectorXd full_g(static_cast<Eigen::Index>(m_dof_count));
  double energy = evaluate_forces(m, m_node_dof, x, rest, all, forces, full_g);
  double force = max_abs(full_g);
  const double tolerance = std::max(m_options.force_tolerance, m_options.relative_force_tolerance * force);

  // Distance along the model's springs from the active muscles' fibres (Dijkstra over rest lengths, mm).
  std::vector<double> distance(nodes, std::numeric_limits<double>::infinity());
  {
    using Item = std::pair<double, Index>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (std::size_t s = 0; s < ns; ++s) {
      const Index k = m.spring_muscle[s];
      if (k < 0 || activations[static_cast<std::size_t>(k)] <= 0.0) continue;
      for (Index node : m.spring_nodes[s]) {
        if (distance[static_cast<std::size_t>(node)] > 0.0) {
          distance[static_cast<std::size_t>(node)] = 0.0;
          queue.emplace(0.0, node);
        }
      }
    }
    while (!queue.empty()) {
      const auto [d, node] = queue.top();
      queue.pop();
      const auto i = static_cast<std::size_t>(node);
      if (d > distance[i]) continue;
      for (std::size_t e = inc.node_neighbour_offsets[i]; e < inc.node_neighbour_offsets[i + 1]; ++e) {
        const auto j = static_cast<std::size_t>(inc.node_neighbours[e]);
        const double dj = d + inc.node_neighbour_mm[e];
        if (dj < distance[j]) {
          distance[j] = dj;
          queue.emplace(dj, static_cast<Index>(j));
        }
      }
    }
  }

  int iteration = 0;
  double margin = m_options.region_margin_mm;
  while (force > tolerance) {
    // The region: free nodes within `margin` of an active fibre; the others are held where they are (at rest).
    std::vector<Index> node_dof(nodes, -1);
    std::vector<std::size_t> region_nodes;
    Eigen::Index dofs = 0;
    bool whole = true;
    for (std::size_t i = 0; i < nodes; ++i) {
      if (m_node_dof[i] < 0) continue;
      if (distance[i] <= margin || margin <= 0.0) {
        region_nodes.push_back(i);
        node_dof[i] = static_cast<Index>(dofs);
        dofs += 3;
      } else {
        whole = false;
      }
    }
    std::vector<char> spring_in(ns, 0), attachment_in(m.attachment_node.size(), 0);
    TermSet set;
    for (std::size_t i = 0; i < nodes; ++i) {
      if (node_dof[i] < 0) continue;
      if (i < m.skin_node_count) set.skin_nodes.push_back(i);
      for (std::size_t t = inc.node_term_offsets[i]; t < inc.node_term_offsets[i + 1]; ++t) {
        const std::size_t term = inc.node_terms[t];
        if (term < ns) {
          spring_in[term] = 1;
        } else {
          attachment_in[term - ns] = 1;
        }
      }
    }
    for (std::size_t s = 0; s < ns; ++s) {
      if (spring_in[s]) set.springs.push_back(s);
    }
    for (std::size_t k = 0; k < attachment_in.size(); ++k) {
      if (attachment_in[k]) set.attachments.push_back(k);
    }
    // H0: the region's projective-dynamics matrix, factored once; applied to x, y and z at once.
    const Eigen::Index n = dofs / 3;
    std::unique_ptr<SparseSpdSolver> h0 = make_sparse_solver(SparseSolverKind::cholmod);
    {
      const SparseMatrix matrix = global_matrix(m, node_dof, set, n);
      h0->analyse(matrix);
      h0->factor(matrix);
    }
    using NodeMajor = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
    Eigen::MatrixXd columns(n, 3), solved(n, 3);
    auto apply_h0 = [&](Eigen::VectorXd& v) {
      NodeMajor view(v.data(), n, 3);
      columns = view;
      h0->solve_columns(columns, solved);
      view = solved;
    };
    auto evaluate = [&](const std::vector<Vec3>& positions, Eigen::VectorXd& gradient) {
      gradient.resize(dofs);
      return evaluate_forces(m, node_dof, positions, rest, set, forces, gradient);
    };
    auto displaced = [&](const std::vector<Vec3>& from, const Eigen::VectorXd& step, double alpha,
                         std::vector<Vec3>& to) {
      // `to` holds the held nodes already (trial starts as a copy of x; they never change).
      for (std::size_t i : region_nodes) to[i] = from[i] + alpha * step.segment<3>(node_dof[i]);
    };
    trial = x;

    Eigen::VectorXd g, trial_g, d;
    energy = evaluate(x, g);
    double region_force = max_abs(g);
    const auto history = static_cast<std::size_t>(m_options.quasi_newton_history);
    std::vector<Eigen::VectorXd> s_history, y_history;
    std::vector<double> rho_history;
    std::vector<double> alpha_history(history);
    for (; iteration < m_options.max_quasi_newton_iterations && region_force > tolerance; ++iteration) {
      // L-BFGS two-loop recursion (Nocedal and Wright, Algorithm 7.4) with H0 = the global matrix's inverse.
      d = -g;
      const std::size_t pairs = s_history.size();
      for (std::size_t j = pairs; j-- > 0;) {
        alpha_history[j] = rho_history[j] * s_history[j].dot(d);
        d -= alpha_history[j] * y_history[j];
      }
      apply_h0(d);
      for (std::size_t j = 0; j < pairs; ++j) {
        const double beta = rho_history[j] * y_history[j].dot(d);
        d += (alpha_history[j] - beta) * s_history[j];
      }
      double slope = g.dot(d);
      if (!(slope < 0.0)) {
        // Not a descent direction (curvature lost): restart from the global matrix alone.
        s_history.clear();
        y_history.clear();
        rho_history.clear();
        d = -g;
        apply_h0(d);
        slope = g.dot(d);
      }
      // Backtracking (Armijo) line search; near the minimum the energy is flat to rounding, where a step that
      // lowers the net force is taken.
      double alpha = 1.0, trial_energy = energy;
      bool accepted = false;
      for (int ls = 0; ls < 40; ++ls) {
        displaced(x, d, alpha, trial);
        trial_energy = evaluate(trial, trial_g);
        if (trial_energy <= energy + 1e-4 * alpha * slope ||
            (std::abs(trial_energy - energy) <= 1e-12 * std::abs(energy) && max_abs(trial_g) < region_force)) {
          accepted = true;
          break;
        }
        alpha *= 0.5;
      }
      if (!accepted) break;
      Eigen::VectorXd s_step = alpha * d;
      Eigen::VectorXd y_step = trial_g - g;
      const double sy = s_step.dot(y_step);
      if (sy > 1e-12 * s_step.squaredNorm()) {
        if (s_history.size() == history) {
          s_history.erase(s_history.begin());
          y_history.erase(y_history.begin());
          rho_history.erase(rho_history.begin());
        }
        s_history.push_back(std::move(s_step));
        y_history.push_back(std::move(y_step));
        rho_history.push_back(1.0 / sy);
      }
      x.swap(trial);
      g.swap(trial_g);
      energy = trial_energy;
      region_force = max_abs(g);
    }
    // The held nodes must be in equilibrium too; else the region grows (the solve goes on from here).
    energy = evaluate_forces(m, m_node_dof, x, rest, all, forces, full_g);
    force = max_abs(full_g);
    if (force <= tolerance || whole || region_force > tolerance) break;
    margin *= 2.0;
  }
  if (!(force <= tolerance)) {
    throw NumericError("muscle contraction: quasi-Newton stopped after " + std::to_string(iteration) +
                       " iterations with net force " + std::to_string(force) + " (tolerance " +
                       std::to_string(tolerance) + ")");
  }
  ContractionResult out;
  out.node_positions = std::move(x);
  out.newton_iterations = iteration;
  out.max_force = force;
  out.energy = energy;
  return out;
}

}  // namespace forensim
