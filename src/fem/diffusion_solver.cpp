#include "fem/diffusion_solver.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fem/tet_element.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/tet_boundary.hpp"

namespace forensim {

namespace {

constexpr double mm2_per_m2 = 1e6;
constexpr double mm_per_m = 1e3;
const std::string source = "diffusion solver";

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
  std::vector<double> face_coefficient;  // cover h c per used face, mm/s * c
  std::vector<double> face_area;
  std::vector<Mat34> grads;
  std::vector<double> volumes;
  std::unique_ptr<SparseSpdSolver> solver;

  bool geometry_dirty = true;
  bool coefficients_dirty = true;
  double factored_dt = -1.0;

  void update_geometry() {
    grads.resize(elements.size());
    volumes.resize(elements.size());
    parallel_for(0, elements.size(), [&](std::size_t e) {
      const Tet& t = elements[e];
      TetCorners p;
      for (int i = 0; i < 4; ++i) p[i] = positions[static_cast<std::size_t>(dof_node[static_cast<std::size_t>(t[i])])];
      grads[e] = tet_shape_gradients(p, &volumes[e]);
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
    // Lumped mass (also 1^T M for the consistent mass): serial, in element order, for determinism.
    lumped_mass.setZero(static_cast<Eigen::Index>(dofs));
    for (std::size_t e = 0; e < elements.size(); ++e) {
      const double c = tet_capacity[static_cast<std::size_t>(active_tets[e])];
      const Vec4 m = tet_lumped_mass(volumes[e], c);
      for (int i = 0; i < 4; ++i) lumped_mass[elements[e][i]] += m[i];
    }
    const bool lumped = settings.lumped_mass;
    pattern.assemble_scalar(
        [&](std::size_t e, Mat4& ke) {
          const std::size_t tet = static_cast<std::size_t>(active_tets[e]);
          const double c = tet_capacity[tet];
          ke = tet_diffusion_stiffness(grads[e], volumes[e], dt * c * tet_diffusivity[tet] * mm2_per_m2);
          if (!lumped) ke += tet_consistent_mass(volumes[e], c);
        },
        system);
    if (lumped) {
      const auto& diag = pattern.diagonal_entries();
      for (std::size_t d = 0; d < dofs; ++d) system.valuePtr()[diag[d]] += lumped_mass[static_cast<Eigen::Index>(d)];
    } else {
      pattern.assemble_scalar(
          [&](std::size_t e, Mat4& me) {
            me = tet_consistent_mass(volumes[e], tet_capacity[static_cast<std::size_t>(active_tets[e])]);
          },
          mass_matrix);
    }
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
          system.valuePtr()[face_entries[k][static_cast<std::size_t>(3 * a + b)]] += dt * off * (a == b ? 2.0 : 1.0);
        load[face_dofs[k][static_cast<std::size_t>(a)]] += coefficient * f.ambient * face_area[k] / 3.0;
      }
    }
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
  s.solver = make_sparse_solver(settings.solver, settings.cg_tolerance);
  if (!s.dof_node.empty()) s.solver->analyse(s.system);
}

DiffusionSolver::~DiffusionSolver() = default;
DiffusionSolver::DiffusionSolver(DiffusionSolver&&) noexcept = default;
DiffusionSolver& DiffusionSolver::operator=(DiffusionSolver&&) noexcept = default;

void DiffusionSolver::set_tet_diffusivity(const std::vector<double>& m2_per_s) {
  require_input(m2_per_s.size() == m_impl->tet_diffusivity.size(), source, "tet diffusivity",
                "wrong size " + std::to_string(m2_per_s.size()));
  for (std::size_t t = 0; t < m2_per_s.size(); ++t) {
    require_input(m_impl->tet_active[t] == 0 || (std::isfinite(m2_per_s[t]) && m2_per_s[t] >= 0.0), source,
                  "tet " + std::to_string(t), "diffusivity must be finite and >= 0");
  }
  m_impl->tet_diffusivity = m2_per_s;
  m_impl->coefficients_dirty = true;
}

void DiffusionSolver::set_tet_capacity(const std::vector<double>& capacity) {
  require_input(capacity.size() == m_impl->tet_capacity.size(), source, "tet capacity",
                "wrong size " + std::to_string(capacity.size()));
  for (std::size_t t = 0; t < capacity.size(); ++t) {
    require_input(m_impl->tet_active[t] == 0 || (std::isfinite(capacity[t]) && capacity[t] > 0.0), source,
                  "tet " + std::to_string(t), "capacity must be finite and > 0");
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
    s.solver->factor(s.system);
    s.factored_dt = dt_s;
    s.coefficients_dirty = false;
    report.refactored = true;
  }
  const std::size_t dofs = s.dof_node.size();
  Eigen::VectorXd old(static_cast<Eigen::Index>(dofs));
  for (std::size_t d = 0; d < dofs; ++d)
    old[static_cast<Eigen::Index>(d)] = values[static_cast<std::size_t>(s.dof_node[d])];
  Eigen::VectorXd rhs =
      s.settings.lumped_mass ? Eigen::VectorXd(s.lumped_mass.cwiseProduct(old)) : Eigen::VectorXd(s.mass_matrix * old);
  rhs += dt_s * s.load;
  Eigen::VectorXd next = old;  // warm start for CG
  s.solver->solve(rhs, next);
  report.iterations = s.solver->last_iterations();
  for (std::size_t d = 0; d < dofs; ++d)
    values[static_cast<std::size_t>(s.dof_node[d])] = next[static_cast<Eigen::Index>(d)];
  report.storage_change = s.lumped_mass.dot(next - old);
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
