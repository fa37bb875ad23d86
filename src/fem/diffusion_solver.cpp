#include "fem/diffusion_solver.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fem/pcg.hpp"
#include "fem/tet_element.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/tet_boundary.hpp"

namespace forensim {

namespace {

constexpr double mm2_per_m2 = 1e6;
constexpr double mm_per_m = 1e3;
const std::string source = "diffusion solver";

Eigen::VectorXd multiplied(const SparseMatrix& a, const Eigen::VectorXd& x) {
  Eigen::VectorXd y;
  symmetric_multiply(a, x, y);
  return y;
}

}  // namespace

std::vector<std::uint8_t> diffusion_active_tets(const TetMesh& mesh) {
  std::vector<std::uint8_t> active(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) active[t] = mesh.label(t) != tissue_bone ? 1 : 0;
  return active;
}

std::vector<RobinFace> skin_robin_faces(const TetMesh& mesh, const std::vector<std::uint8_t>& tet_active,
                                        double transfer_m_per_s, double ambient) {
  std::vector<RobinFace> faces;
  for (const TetFace& f : tet_boundary_faces(mesh)) {
    if (!tet_active.empty() && tet_active[static_cast<std::size_t>(f.tet)] == 0) continue;
    faces.push_back(RobinFace{f.vertices, f.tet, transfer_m_per_s, ambient, 1.0});
  }
  return faces;
}

/// The six edges of a tet as corner pairs, and the edge of a corner pair (a != b).
constexpr std::array<std::array<int, 2>, 6> tet_edges{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

struct DiffusionSolver::Impl {
  DiffusionSettings settings;
  std::size_t node_count = 0;
  std::vector<Vec3> positions;
  std::vector<std::uint8_t> tet_active;
  std::vector<Index> node_dof;     // #V, -1 when inactive
  std::vector<Index> dof_node;     // active nodes
  std::vector<Index> active_tets;  // mesh tet of each element
  std::vector<Tet> elements;       // active tets in dof numbering
  std::vector<Tet> mesh_tets;      // active tets in mesh numbering
  std::vector<double> tet_diffusivity;
  std::vector<double> tet_capacity;

  std::vector<RobinFace> faces;                             // as given
  std::vector<std::size_t> used_faces;                      // faces of active tets
  std::vector<std::array<Index, 3>> face_dofs;              // per used face
  std::vector<std::array<std::ptrdiff_t, 9>> face_entries;  // value indices of the 3x3 block

  SparsityPattern pattern;
  SparseMatrix system;                   // M + dt (K + H)
  SparseMatrix mass_matrix;              // consistent M (when not lumped)
  Eigen::VectorXd lumped_mass;           // row sums of M (= 1^T M for either M)
  Eigen::VectorXd load;                  // f, per dof (without dt)
  Eigen::VectorXd inverse_diagonal;      // Jacobi preconditioner of `system`
  std::vector<double> face_coefficient;  // cover h c per used face, mm/s * c
  std::vector<double> face_area;
  std::vector<double> volumes;
  /// Per element, the unit-coefficient stiffness of its six edges, V grad N_a . grad N_b (eq. 11 with
  /// k = 1): the off-diagonal entries of K_e; the diagonal follows from zero row sums.
  std::vector<std::array<double, 6>> edge_stiffness;
  /// Reassembly as a gather (no colours, no atomics, parallel over matrix columns): for value index k,
  /// entry_sources[entry_start[k] .. entry_start[k + 1]) are the element edges (6 e + edge) that contribute
  /// to it, in element order (empty for diagonal entries). dof_elements likewise lists each dof's elements.
  std::vector<int> entry_start, entry_sources;
  std::vector<int> dof_start, dof_elements;
  /// The mesh edges: the value index of each edge's entry above the diagonal, and per value index its edge
  /// (-1 on the diagonal). assemble() gathers each edge once for its two symmetric entries.
  std::vector<std::ptrdiff_t> edge_entry;
  std::vector<int> entry_edge;
  /// The same sources in mesh-edge order, each edge's together (edge_source_start), as the element and that
  /// element edge's stiffness (refreshed by update_geometry): the gather of assemble() then reads them in
  /// sequence and only the per-element coefficient at random.
  std::vector<int> edge_source_start, edge_source_element;
  std::vector<double> edge_source_stiffness;
  std::vector<double> edge_value, edge_mass;    // scratch of assemble(): K_ab and the consistent-mass sum
  std::vector<double> element_coefficient;      // dt c D (mm^2) per element, scratch of assemble()
  std::vector<double> element_capacity_volume;  // c V per element, scratch of assemble()
  std::unique_ptr<SparseSpdSolver> solver;      // cholmod / cg_ic backends

  bool geometry_dirty = true;
  bool coefficients_dirty = true;
  double factored_dt = -1.0;

  void build_gather_maps() {
    const std::size_t nnz = pattern.nonzero_count();
    const std::size_t ne = elements.size();
    std::vector<std::array<std::ptrdiff_t, 12>> entries(ne);
    parallel_for(0, ne, [&](std::size_t e) {
      const Tet& t = elements[e];
      for (std::size_t j = 0; j < 6; ++j) {
        const Index a = t[static_cast<std::size_t>(tet_edges[j][0])];
        const Index b = t[static_cast<std::size_t>(tet_edges[j][1])];
        entries[e][2 * j] = pattern.entry(a, b);
        entries[e][2 * j + 1] = pattern.entry(b, a);
      }
    });
    entry_start.assign(nnz + 1, 0);
    for (const auto& list : entries)
      for (std::ptrdiff_t k : list) ++entry_start[static_cast<std::size_t>(k) + 1];
    for (std::size_t k = 0; k < nnz; ++k) entry_start[k + 1] += entry_start[k];
    entry_sources.assign(static_cast<std::size_t>(entry_start[nnz]), 0);
    std::vector<int> fill(entry_start.begin(), entry_start.end() - 1);
    for (std::size_t e = 0; e < ne; ++e) {
      for (std::size_t i = 0; i < 12; ++i) {
        const auto k = static_cast<std::size_t>(entries[e][i]);
        entry_sources[static_cast<std::size_t>(fill[k]++)] = static_cast<int>(6 * e + i / 2);
      }
    }
    const int* outer = system.outerIndexPtr();
    const int* inner = system.innerIndexPtr();
    const auto columns = static_cast<std::size_t>(system.cols());
    entry_edge.assign(nnz, -1);
    edge_entry.clear();
    for (std::size_t j = 0; j < columns; ++j) {
      for (int k = outer[j]; k < outer[j + 1]; ++k) {
        if (static_cast<std::size_t>(inner[k]) < j) {
          entry_edge[static_cast<std::size_t>(k)] = static_cast<int>(edge_entry.size());
          edge_entry.push_back(k);
        }
      }
    }
    for (std::size_t j = 0; j < columns; ++j) {
      for (int k = outer[j]; k < outer[j + 1]; ++k) {
        if (static_cast<std::size_t>(inner[k]) > j) {
          const std::ptrdiff_t mirror = pattern.entry(static_cast<Index>(j), inner[k]);
          entry_edge[static_cast<std::size_t>(k)] = entry_edge[static_cast<std::size_t>(mirror)];
        }
      }
    }
    edge_source_start.assign(edge_entry.size() + 1, 0);
    for (std::size_t edge = 0; edge < edge_entry.size(); ++edge) {
      const auto k = static_cast<std::size_t>(edge_entry[edge]);
      edge_source_start[edge + 1] = edge_source_start[edge] + (entry_start[k + 1] - entry_start[k]);
    }
    edge_source_element.assign(static_cast<std::size_t>(edge_source_start.back()), 0);
    for (std::size_t edge = 0; edge < edge_entry.size(); ++edge) {
      const auto k = static_cast<std::size_t>(edge_entry[edge]);
      int out = edge_source_start[edge];
      for (int i = entry_start[k]; i < entry_start[k + 1]; ++i)
        edge_source_element[static_cast<std::size_t>(out++)] = entry_sources[static_cast<std::size_t>(i)] / 6;
    }
    const std::size_t dofs = dof_node.size();
    dof_start.assign(dofs + 1, 0);
    for (const Tet& t : elements)
      for (Index d : t) ++dof_start[static_cast<std::size_t>(d) + 1];
    for (std::size_t d = 0; d < dofs; ++d) dof_start[d + 1] += dof_start[d];
    dof_elements.assign(static_cast<std::size_t>(dof_start[dofs]), 0);
    fill.assign(dof_start.begin(), dof_start.end() - 1);
    for (std::size_t e = 0; e < ne; ++e)
      for (Index d : elements[e])
        dof_elements[static_cast<std::size_t>(fill[static_cast<std::size_t>(d)]++)] = static_cast<int>(e);
  }

  void update_geometry() {
    edge_stiffness.resize(elements.size());
    volumes.resize(elements.size());
    parallel_for(
        0, elements.size(),
        [&](std::size_t e) {
          const Tet& t = elements[e];
          TetCorners p;
          for (int i = 0; i < 4; ++i)
            p[static_cast<std::size_t>(i)] =
                positions[static_cast<std::size_t>(dof_node[static_cast<std::size_t>(t[i])])];
          const Mat34 g = tet_shape_gradients(p, &volumes[e]);
          for (std::size_t j = 0; j < 6; ++j)
            edge_stiffness[e][j] = volumes[e] * g.col(tet_edges[j][0]).dot(g.col(tet_edges[j][1]));
        },
        1024);
    edge_source_stiffness.resize(edge_source_element.size());
    parallel_for_chunks(0, edge_entry.size(), [&](std::size_t lo, std::size_t hi) {
      for (std::size_t edge = lo; edge < hi; ++edge) {
        const auto k = static_cast<std::size_t>(edge_entry[edge]);
        int out = edge_source_start[edge];
        for (int i = entry_start[k]; i < entry_start[k + 1]; ++i) {
          const auto src = static_cast<std::size_t>(entry_sources[static_cast<std::size_t>(i)]);
          edge_source_stiffness[static_cast<std::size_t>(out++)] = edge_stiffness[src / 6][src % 6];
        }
      }
    });
    face_area.resize(used_faces.size());
    for (std::size_t k = 0; k < used_faces.size(); ++k) {
      const Tri& v = faces[used_faces[k]].vertices;
      face_area[k] = triangle_area(positions[static_cast<std::size_t>(v[0])], positions[static_cast<std::size_t>(v[1])],
                                   positions[static_cast<std::size_t>(v[2])]);
    }
    geometry_dirty = false;
  }

  void assemble(double dt) {
    const std::size_t dofs = dof_node.size();
    const std::size_t ne = elements.size();
    element_coefficient.resize(ne);
    element_capacity_volume.resize(ne);
    parallel_for_chunks(0, ne, [&](std::size_t lo, std::size_t hi) {
      for (std::size_t e = lo; e < hi; ++e) {
        const auto tet = static_cast<std::size_t>(active_tets[e]);
        element_coefficient[e] = dt * tet_capacity[tet] * tet_diffusivity[tet] * mm2_per_m2;
        element_capacity_volume[e] = tet_capacity[tet] * volumes[e];
      }
    });
    const bool lumped = settings.lumped_mass;
    lumped_mass.resize(static_cast<Eigen::Index>(dofs));
    const int* outer = system.outerIndexPtr();
    const int* inner = system.innerIndexPtr();
    double* values = system.valuePtr();
    double* mass_values = lumped ? nullptr : mass_matrix.valuePtr();
    // Per mesh edge (both of its entries get the same value): K_ab gathered from the element edges.
    edge_value.resize(edge_entry.size());
    if (!lumped) edge_mass.resize(edge_entry.size());
    parallel_for_chunks(0, edge_entry.size(), [&](std::size_t lo, std::size_t hi) {
      for (std::size_t edge = lo; edge < hi; ++edge) {
        double v = 0.0, m = 0.0;
        for (int i = edge_source_start[edge]; i < edge_source_start[edge + 1]; ++i) {
          const auto element = static_cast<std::size_t>(edge_source_element[static_cast<std::size_t>(i)]);
          v += element_coefficient[element] * edge_source_stiffness[static_cast<std::size_t>(i)];
          if (!lumped) m += element_capacity_volume[element];
        }
        edge_value[edge] = v;
        if (!lumped) edge_mass[edge] = m;
      }
    });
    // Column j (= row j): K off-diagonals from the edges, K_jj = -(their sum) (rows of K sum
    // to zero exactly, so 1^T K u = 0 and the water balance has no assembly error), plus M.
    parallel_for_chunks(
        0, dofs,
        [&](std::size_t lo, std::size_t hi) {
          for (std::size_t j = lo; j < hi; ++j) {
            double capacity_volume = 0.0;
            for (int i = dof_start[j]; i < dof_start[j + 1]; ++i)
              capacity_volume +=
                  element_capacity_volume[static_cast<std::size_t>(dof_elements[static_cast<std::size_t>(i)])];
            lumped_mass[static_cast<Eigen::Index>(j)] = capacity_volume / 4.0;  // tet_lumped_mass per corner
            double off_sum = 0.0;
            int diagonal = -1;
            for (int k = outer[j]; k < outer[j + 1]; ++k) {
              if (static_cast<std::size_t>(inner[k]) == j) {
                diagonal = k;
                continue;
              }
              const auto edge = static_cast<std::size_t>(entry_edge[static_cast<std::size_t>(k)]);
              const double v = edge_value[edge];
              off_sum += v;
              if (lumped) {
                values[k] = v;
              } else {
                values[k] = v + edge_mass[edge] / 20.0;  // tet_consistent_mass off-diagonal c V / 20
                mass_values[k] = edge_mass[edge] / 20.0;
              }
            }
            if (lumped) {
              values[diagonal] = lumped_mass[static_cast<Eigen::Index>(j)] - off_sum;
            } else {
              values[diagonal] = capacity_volume / 10.0 - off_sum;  // c V / 10 per element on the diagonal
              mass_values[diagonal] = capacity_volume / 10.0;
            }
          }
        },
        512);
    load.setZero(static_cast<Eigen::Index>(dofs));
    face_coefficient.resize(used_faces.size());
    for (std::size_t k = 0; k < used_faces.size(); ++k) {
      const RobinFace& f = faces[used_faces[k]];
      const double coefficient =
          f.cover * f.transfer_m_per_s * mm_per_m * tet_capacity[static_cast<std::size_t>(f.tet)];
      face_coefficient[k] = coefficient;
      // H_f = coefficient A (1 + delta_ij) / 12 (eq. 13), f_f = coefficient phi_e A / 3 (eq. 14).
      const double off = coefficient * face_area[k] / 12.0;
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b)
          values[face_entries[k][static_cast<std::size_t>(3 * a + b)]] += dt * off * (a == b ? 2.0 : 1.0);
        load[face_dofs[k][static_cast<std::size_t>(a)]] += coefficient * f.ambient * face_area[k] / 3.0;
      }
    }
    inverse_diagonal.resize(static_cast<Eigen::Index>(dofs));
    const auto& diag = pattern.diagonal_entries();
    parallel_for_chunks(0, dofs, [&](std::size_t lo, std::size_t hi) {
      for (std::size_t d = lo; d < hi; ++d) inverse_diagonal[static_cast<Eigen::Index>(d)] = 1.0 / values[diag[d]];
    });
  }

  /// Jacobi-preconditioned CG with the stopping tests of DiffusionSettings; returns the iterations.
  int solve_jacobi_cg(const Eigen::VectorXd& rhs, const Eigen::VectorXd& old, Eigen::VectorXd& next) const {
    const std::size_t n = static_cast<std::size_t>(rhs.size());
    const double* r_inv = inverse_diagonal.data();
    double scale = 0.0, rhs_size = 0.0;
    for (Eigen::Index d = 0; d < old.size(); ++d) {
      scale = std::max(scale, std::abs(old[d]));
      rhs_size += std::abs(rhs[d]);
    }
    const double correction_limit = settings.tolerance * scale;
    const double balance_limit = settings.balance_tolerance * rhs_size;
    const LinearOperator a = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
      symmetric_multiply(system, in, out);
    };
    const LinearOperator jacobi = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
      out.resize(in.size());
      parallel_for_chunks(0, n, [&](std::size_t lo, std::size_t hi) {
        for (std::size_t i = lo; i < hi; ++i)
          out[static_cast<Eigen::Index>(i)] = r_inv[i] * in[static_cast<Eigen::Index>(i)];
      });
    };
    const PcgConverged converged = [&](const Eigen::VectorXd& r, int) {
      const double* pr = r.data();
      const double unbalanced = parallel_sum_chunks(0, n, [&](std::size_t lo, std::size_t hi) {
        double s = 0.0;
        for (std::size_t i = lo; i < hi; ++i) s += pr[i];
        return s;
      });
      if (std::abs(unbalanced) > balance_limit) return false;
      for (std::size_t i = 0; i < n; ++i)
        if (std::abs(pr[i]) * r_inv[i] > correction_limit) return false;
      return true;
    };
    const PcgResult result = preconditioned_cg(a, jacobi, rhs, next, converged, settings.max_iterations);
    if (!result.converged) {
      throw NumericError("diffusion solver: CG did not converge in " + std::to_string(result.iterations) +
                         " iterations");
    }
    return result.iterations;
  }
};

DiffusionSolver::DiffusionSolver(const TetMesh& mesh, std::vector<std::uint8_t> tet_active,
                                 const std::vector<RobinFace>& faces, DiffusionSettings settings)
    : m_impl(std::make_unique<Impl>()) {
  Impl& s = *m_impl;
  s.settings = settings;
  s.node_count = mesh.vertex_count();
  s.positions = mesh.positions;
  if (tet_active.empty()) tet_active.assign(mesh.tet_count(), 1);
  require_input(
      tet_active.size() == mesh.tet_count(), source, "tet_active",
      "has " + std::to_string(tet_active.size()) + " entries for " + std::to_string(mesh.tet_count()) + " tets");
  s.tet_active = std::move(tet_active);
  s.node_dof.assign(s.node_count, -1);
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (s.tet_active[t] == 0) continue;
    for (Index n : mesh.tets[t]) {
      require_input(n >= 0 && static_cast<std::size_t>(n) < s.node_count, source, "tet " + std::to_string(t),
                    "node index " + std::to_string(n) + " out of range");
      s.node_dof[static_cast<std::size_t>(n)] = 0;
    }
  }
  for (std::size_t n = 0; n < s.node_count; ++n) {
    if (s.node_dof[n] == 0) {
      s.node_dof[n] = static_cast<Index>(s.dof_node.size());
      s.dof_node.push_back(static_cast<Index>(n));
    }
  }
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (s.tet_active[t] == 0) continue;
    Tet e;
    for (int i = 0; i < 4; ++i) e[i] = s.node_dof[static_cast<std::size_t>(mesh.tets[t][i])];
    s.active_tets.push_back(static_cast<Index>(t));
    s.elements.push_back(e);
    s.mesh_tets.push_back(mesh.tets[t]);
  }
  s.tet_diffusivity.assign(mesh.tet_count(), 1e-9);
  s.tet_capacity.assign(mesh.tet_count(), 1.0);
  s.pattern = SparsityPattern(s.elements, s.dof_node.size(), 1);
  s.system = s.pattern.make_matrix();
  if (!settings.lumped_mass) s.mass_matrix = s.pattern.make_matrix();

  s.faces = faces;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const RobinFace& f = faces[k];
    require_input(f.tet >= 0 && static_cast<std::size_t>(f.tet) < mesh.tet_count(), source, "face " + std::to_string(k),
                  "tet index " + std::to_string(f.tet) + " out of range");
    if (s.tet_active[static_cast<std::size_t>(f.tet)] == 0) continue;
    std::array<Index, 3> dofs{};
    for (int i = 0; i < 3; ++i) {
      const Index n = f.vertices[static_cast<std::size_t>(i)];
      require_input(n >= 0 && static_cast<std::size_t>(n) < s.node_count, source, "face " + std::to_string(k),
                    "node index " + std::to_string(n) + " out of range");
      dofs[static_cast<std::size_t>(i)] = s.node_dof[static_cast<std::size_t>(n)];
    }
    std::array<std::ptrdiff_t, 9> entries{};
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        entries[static_cast<std::size_t>(3 * a + b)] =
            s.pattern.entry(dofs[static_cast<std::size_t>(a)], dofs[static_cast<std::size_t>(b)]);
        require_input(entries[static_cast<std::size_t>(3 * a + b)] >= 0, source, "face " + std::to_string(k),
                      "is not a face of an active tet");
      }
    }
    s.used_faces.push_back(k);
    s.face_dofs.push_back(dofs);
    s.face_entries.push_back(entries);
  }
  s.build_gather_maps();
  if (settings.solver != SparseSolverKind::cg_jacobi) {
    s.solver = make_sparse_solver(settings.solver, settings.cg_tolerance);
    if (!s.dof_node.empty()) s.solver->analyse(s.system);
  }
}

DiffusionSolver::~DiffusionSolver() = default;
DiffusionSolver::DiffusionSolver(DiffusionSolver&&) noexcept = default;
DiffusionSolver& DiffusionSolver::operator=(DiffusionSolver&&) noexcept = default;

void DiffusionSolver::set_tet_diffusivity(const std::vector<double>& m2_per_s) {
  require_input(m2_per_s.size() == m_impl->tet_diffusivity.size(), source, "tet diffusivity",
                "wrong size " + std::to_string(m2_per_s.size()));
  for (std::size_t t = 0; t < m2_per_s.size(); ++t) {
    if (m_impl->tet_active[t] != 0 && !(std::isfinite(m2_per_s[t]) && m2_per_s[t] >= 0.0))
      throw InputError(source, "tet " + std::to_string(t), "diffusivity must be finite and >= 0");
  }
  m_impl->tet_diffusivity = m2_per_s;
  m_impl->coefficients_dirty = true;
}

void DiffusionSolver::set_tet_capacity(const std::vector<double>& capacity) {
  require_input(capacity.size() == m_impl->tet_capacity.size(), source, "tet capacity",
                "wrong size " + std::to_string(capacity.size()));
  for (std::size_t t = 0; t < capacity.size(); ++t) {
    if (m_impl->tet_active[t] != 0 && !(std::isfinite(capacity[t]) && capacity[t] > 0.0))
      throw InputError(source, "tet " + std::to_string(t), "capacity must be finite and > 0");
  }
  m_impl->tet_capacity = capacity;
  m_impl->coefficients_dirty = true;
}

void DiffusionSolver::set_face_cover(const std::vector<double>& cover) {
  require_input(cover.size() == m_impl->faces.size(), source, "face cover",
                "wrong size " + std::to_string(cover.size()));
  for (std::size_t k = 0; k < cover.size(); ++k) {
    require_input(std::isfinite(cover[k]) && cover[k] >= 0.0, source, "face " + std::to_string(k),
                  "cover must be finite and >= 0");
    m_impl->faces[k].cover = cover[k];
  }
  m_impl->coefficients_dirty = true;
}

void DiffusionSolver::set_face_ambient(const std::vector<double>& ambient) {
  require_input(ambient.size() == m_impl->faces.size(), source, "face ambient",
                "wrong size " + std::to_string(ambient.size()));
  for (std::size_t k = 0; k < ambient.size(); ++k) m_impl->faces[k].ambient = ambient[k];
  m_impl->coefficients_dirty = true;  // only f changes, but f is rebuilt with the matrix
}

void DiffusionSolver::set_positions(const std::vector<Vec3>& positions_mm) {
  require_input(positions_mm.size() == m_impl->node_count, source, "positions",
                "wrong size " + std::to_string(positions_mm.size()));
  if (positions_mm == m_impl->positions) return;  // unchanged (the shape is solved every few steps)
  m_impl->positions = positions_mm;
  m_impl->geometry_dirty = true;
}

DiffusionStepReport DiffusionSolver::step(std::vector<double>& values, double dt_s) {
  Impl& s = *m_impl;
  require_input(values.size() == s.node_count, source, "values", "wrong size " + std::to_string(values.size()));
  require_input(std::isfinite(dt_s) && dt_s > 0.0, source, "dt", "time step must be > 0");
  DiffusionStepReport report;
  if (s.dof_node.empty()) return report;  // nothing takes part (all bone)
  if (s.geometry_dirty) {
    s.update_geometry();
    s.coefficients_dirty = true;
  }
  if (s.coefficients_dirty || dt_s != s.factored_dt) {
    s.assemble(dt_s);
    if (s.solver) s.solver->factor(s.system);
    s.factored_dt = dt_s;
    s.coefficients_dirty = false;
    report.refactored = true;
  }
  const std::size_t dofs = s.dof_node.size();
  Eigen::VectorXd old(static_cast<Eigen::Index>(dofs));
  for (std::size_t d = 0; d < dofs; ++d)
    old[static_cast<Eigen::Index>(d)] = values[static_cast<std::size_t>(s.dof_node[d])];
  Eigen::VectorXd rhs =
      s.settings.lumped_mass ? Eigen::VectorXd(s.lumped_mass.cwiseProduct(old)) : multiplied(s.mass_matrix, old);
  rhs += dt_s * s.load;
  Eigen::VectorXd next = old;  // warm start for CG
  if (s.solver) {
    s.solver->solve(rhs, next);
    report.iterations = s.solver->last_iterations();
  } else {
    report.iterations = s.solve_jacobi_cg(rhs, old, next);
  }
  for (std::size_t d = 0; d < dofs; ++d)
    values[static_cast<std::size_t>(s.dof_node[d])] = next[static_cast<Eigen::Index>(d)];
  const Eigen::VectorXd change = next - old;
  report.storage_change = parallel_dot(s.lumped_mass, change);
  double outflow = 0.0;
  for (std::size_t k = 0; k < s.used_faces.size(); ++k) {
    const auto& d = s.face_dofs[k];
    const double sum = next[d[0]] + next[d[1]] + next[d[2]];
    outflow += s.face_coefficient[k] * s.face_area[k] / 3.0 * (sum - 3.0 * s.faces[s.used_faces[k]].ambient);
  }
  report.boundary_outflow = dt_s * outflow;
  return report;
}

double DiffusionSolver::total_content(const std::vector<double>& values) const {
  const Impl& s = *m_impl;
  require_input(values.size() == s.node_count, source, "values", "wrong size " + std::to_string(values.size()));
  // 1^T M u with the current capacities (exact integral of c u for P1 u and per-tet constant c).
  double total = 0.0;
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    const double c = s.tet_capacity[static_cast<std::size_t>(s.active_tets[e])];
    const Tet& t = s.mesh_tets[e];
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) sum += values[static_cast<std::size_t>(t[i])];
    const TetCorners p{s.positions[static_cast<std::size_t>(t[0])], s.positions[static_cast<std::size_t>(t[1])],
                       s.positions[static_cast<std::size_t>(t[2])], s.positions[static_cast<std::size_t>(t[3])]};
    total += c * tet_volume(p) * sum / 4.0;
  }
  return total;
}

std::size_t DiffusionSolver::active_node_count() const {
  return m_impl->dof_node.size();
}

bool DiffusionSolver::node_active(Index n) const {
  return n >= 0 && static_cast<std::size_t>(n) < m_impl->node_count &&
         m_impl->node_dof[static_cast<std::size_t>(n)] >= 0;
}

const SparsityPattern& DiffusionSolver::pattern() const {
  return m_impl->pattern;
}

const SparseMatrix& DiffusionSolver::system_matrix() const {
  return m_impl->system;
}

double diffuse(const TetMesh& mesh, const std::vector<RobinFace>& faces, double diffusivity_m2_per_s, double dt_s,
               int steps, std::vector<double>& values) {
  const auto active = diffusion_active_tets(mesh);
  DiffusionSolver solver(mesh, active, faces);
  solver.set_tet_diffusivity(std::vector<double>(mesh.tet_count(), diffusivity_m2_per_s));
  double outflow = 0.0;
  for (int s = 0; s < steps; ++s) outflow += solver.step(values, dt_s).boundary_outflow;
  return outflow;
}

}  // namespace forensim
