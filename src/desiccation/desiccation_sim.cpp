#include "desiccation/desiccation_sim.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/atomic_file.hpp"
#include "core/byte_record.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {

namespace {

constexpr double kg_per_m3_mm3 = 1e-9;  // (kg/m^3) * mm^3 -> kg

double tet_volume_at(const std::vector<Vec3>& p, const Tet& t) {
  return tet_signed_volume(p[static_cast<std::size_t>(t[0])], p[static_cast<std::size_t>(t[1])],
                           p[static_cast<std::size_t>(t[2])], p[static_cast<std::size_t>(t[3])]);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void check_state(const DesiccationModel& model, const DesiccationState& state) {
  const std::size_t n = model.body.volume.vertex_count();
  require_input(state.node_moisture.size() == n && state.positions.size() == n && state.velocities.size() == n,
                "desiccation state", "", "arrays must hold one entry per volume node (" + std::to_string(n) + ")");
}

}  // namespace

void DesiccationSettings::validate(const std::string& source) const {
  tissue.validate(source);
  environment.validate(source);
  for (const ElasticMaterial* m : {&materials.flesh, &materials.bone}) {
    require_input(std::isfinite(m->youngs_modulus_pa) && m->youngs_modulus_pa > 0.0 && m->poisson_ratio > -1.0 &&
                      m->poisson_ratio < 0.5 && m->density_kg_per_m3 > 0.0,
                  source, "materials", "need E > 0, -1 < nu < 0.5 and density > 0");
  }
}

DesiccationModel make_desiccation_model(BodyModel body, const DesiccationSettings& settings) {
  settings.validate("desiccation settings");
  body.volume.validate("body volume");
  DesiccationModel model;
  model.settings = settings;
  model.body = std::move(body);
  const TetMesh& mesh = model.body.volume;
  model.tet_rest_volume_mm3.resize(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    model.tet_rest_volume_mm3[t] = tet_volume_at(mesh.positions, mesh.tets[t]);
    require_input(model.tet_rest_volume_mm3[t] > 0.0, "body volume", "tet " + std::to_string(t),
                  "has non-positive volume");
  }
  model.tet_active = diffusion_active_tets(mesh);
  model.equilibrium_moisture =
      equilibrium_moisture(settings.environment.isotherm, settings.environment.relative_humidity);
  model.transfer_m_per_s = surface_transfer_m_per_s(settings.environment, settings.tissue);
  model.skin_faces = skin_robin_faces(mesh, model.tet_active, model.transfer_m_per_s, model.equilibrium_moisture);
  std::vector<Tri> tris;
  tris.reserve(model.skin_faces.size());
  for (const RobinFace& f : model.skin_faces) tris.push_back(f.vertices);
  const std::vector<double> cover = face_cover(mesh.positions, tris, settings.environment);
  for (std::size_t f = 0; f < cover.size(); ++f) model.skin_faces[f].cover = cover[f];
  return model;
}

DesiccationState initial_desiccation_state(const DesiccationModel& model) {
  const TetMesh& mesh = model.body.volume;
  DesiccationState state;
  state.node_moisture.assign(mesh.vertex_count(), 0.0);
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (!model.tet_active[t]) continue;
    for (Index v : mesh.tets[t])
      state.node_moisture[static_cast<std::size_t>(v)] = model.settings.tissue.initial_moisture;
  }
  state.positions = mesh.positions;
  state.velocities.assign(mesh.vertex_count(), Vec3::Zero());
  return state;
}

namespace {

void tet_moisture_into(const DesiccationModel& model, const DesiccationState& state, std::vector<double>& x) {
  const TetMesh& mesh = model.body.volume;
  if (x.size() != mesh.tet_count())
    x = std::vector<double>(mesh.tet_count());  // resize() trips GCC 12's -Wnull-dereference
  parallel_for_chunks(0, mesh.tet_count(), [&](std::size_t lo, std::size_t hi) {
    for (std::size_t t = lo; t < hi; ++t) {
      double sum = 0.0;
      if (model.tet_active[t]) {
        for (Index v : mesh.tets[t]) sum += state.node_moisture[static_cast<std::size_t>(v)];
      }
      x[t] = 0.25 * sum;
    }
  });
}

}  // namespace

std::vector<double> tet_moisture(const DesiccationModel& model, const DesiccationState& state) {
  std::vector<double> x;
  tet_moisture_into(model, state, x);
  return x;
}

std::vector<double> tet_volume_ratio(const DesiccationModel& model, const DesiccationState& state) {
  std::vector<double> x = tet_moisture(model, state);
  for (std::size_t t = 0; t < x.size(); ++t)
    x[t] = model.tet_active[t] ? volume_ratio(model.settings.tissue, x[t]) : 1.0;
  return x;
}

std::size_t inverted_tet_count(const TetMesh& mesh, const std::vector<Vec3>& positions) {
  const double count = parallel_sum_chunks(0, mesh.tet_count(), [&](std::size_t lo, std::size_t hi) {
    double n = 0.0;
    for (std::size_t t = lo; t < hi; ++t) n += tet_volume_at(positions, mesh.tets[t]) <= 0.0 ? 1.0 : 0.0;
    return n;
  });
  return static_cast<std::size_t>(count);
}

DesiccationTotals desiccation_totals(const DesiccationModel& model, const DesiccationState& state) {
  check_state(model, state);
  const TetMesh& mesh = model.body.volume;
  const double rho_d0 = dry_solid_density_kg_per_m3(model.settings.tissue);
  const double rho_bone = model.settings.materials.bone.density_kg_per_m3;
  const std::size_t parts = model.body.part_names.size();
  const bool have_parts = parts > 0 && model.body.tet_parts.size() == mesh.tet_count();
  DesiccationTotals totals;
  if (have_parts) {
    totals.part_water_kg.assign(parts, 0.0);
    totals.part_total_kg.assign(parts, 0.0);
    totals.part_volume_mm3.assign(parts, 0.0);
  }
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const double v0 = model.tet_rest_volume_mm3[t];
    const double v = tet_volume_at(state.positions, mesh.tets[t]);
    double water = 0.0, solid = 0.0;
    if (model.tet_active[t]) {
      double sum = 0.0;
      for (Index n : mesh.tets[t]) sum += state.node_moisture[static_cast<std::size_t>(n)];
      solid = rho_d0 * v0 * kg_per_m3_mm3;
      water = solid * 0.25 * sum;
      totals.water_kg += water;
      totals.dry_kg += solid;
    } else {
      solid = rho_bone * v0 * kg_per_m3_mm3;
      totals.bone_kg += solid;
    }
    totals.volume_mm3 += v;
    if (have_parts) {
      const int p = model.body.tet_parts[t];
      if (p >= 0 && static_cast<std::size_t>(p) < parts) {
        totals.part_water_kg[static_cast<std::size_t>(p)] += water;
        totals.part_total_kg[static_cast<std::size_t>(p)] += water + solid;
        totals.part_volume_mm3[static_cast<std::size_t>(p)] += v;
      }
    }
  }
  totals.total_kg = totals.water_kg + totals.dry_kg + totals.bone_kg;
  return totals;
}

struct DesiccationSolver::Impl {
  const DesiccationModel* model = nullptr;
  DiffusionSolver diffusion;
  std::unique_ptr<CorotationalSolver> elastic;
  std::vector<double> capacity, diffusivity, strain, scratch;

  explicit Impl(const DesiccationModel& m)
      : model(&m), diffusion(m.body.volume, m.tet_active, m.skin_faces, m.settings.diffusion) {
    if (m.settings.deform) {
      const ElasticMaterials materials =
          elastic_materials_from_labels(m.body.volume, m.settings.materials.flesh, m.settings.materials.bone);
      elastic = std::make_unique<CorotationalSolver>(m.body.volume, materials, m.settings.elastic);
    }
    capacity.assign(m.body.volume.tet_count(), 1.0);
    diffusivity.assign(m.body.volume.tet_count(), m.settings.tissue.reference_diffusivity_m2_per_s);
    strain.assign(m.body.volume.tet_count(), 0.0);
  }
};

DesiccationSolver::DesiccationSolver(const DesiccationModel& model) : m_impl(std::make_unique<Impl>(model)) {}
DesiccationSolver::~DesiccationSolver() = default;
DesiccationSolver::DesiccationSolver(DesiccationSolver&&) noexcept = default;
DesiccationSolver& DesiccationSolver::operator=(DesiccationSolver&&) noexcept = default;

DesiccationStepReport DesiccationSolver::step(DesiccationState& state, double dt_s, bool deform) {
  Impl& s = *m_impl;
  const DesiccationModel& model = *s.model;
  check_state(model, state);
  require_input(std::isfinite(dt_s) && dt_s > 0.0, "desiccation step", "dt", "must be a positive number of seconds");
  const TetMesh& mesh = model.body.volume;
  const TissueDrying& tissue = model.settings.tissue;
  const double rho_d0 = dry_solid_density_kg_per_m3(tissue);
  DesiccationStepReport report;

  // Moisture: capacity = dry mass per current volume (eq. 7 with the actual volume ratio), D from moisture.
  auto start = std::chrono::steady_clock::now();
  std::vector<double>& x_tet = s.scratch;
  tet_moisture_into(model, state, x_tet);
  std::atomic<std::size_t> inverted_tet{mesh.tet_count()};
  parallel_for_chunks(0, mesh.tet_count(), [&](std::size_t lo, std::size_t hi) {
    for (std::size_t t = lo; t < hi; ++t) {
      if (!model.tet_active[t]) continue;
      const double v = tet_volume_at(state.positions, mesh.tets[t]);
      if (!(v > 0.0)) {
        std::size_t current = inverted_tet.load();
        while (t < current && !inverted_tet.compare_exchange_weak(current, t)) {
        }
        continue;
      }
      s.capacity[t] = rho_d0 * model.tet_rest_volume_mm3[t] / v;
      s.diffusivity[t] = moisture_diffusivity_m2_per_s(tissue, x_tet[t]);
    }
  });
  if (inverted_tet.load() < mesh.tet_count())
    throw NumericError("desiccation step: tet " + std::to_string(inverted_tet.load()) + " is inverted");
  s.diffusion.set_positions(state.positions);
  s.diffusion.set_tet_capacity(s.capacity);
  s.diffusion.set_tet_diffusivity(s.diffusivity);
  const DiffusionStepReport moisture = s.diffusion.step(state.node_moisture, dt_s);
  report.evaporated_kg = moisture.boundary_outflow * kg_per_m3_mm3;
  report.diffusion_iterations = moisture.iterations;
  state.evaporated_kg += report.evaporated_kg;
  report.seconds_diffusion = seconds_since(start);

  // Shrinkage strain per tet from its new moisture (eq. 28; strain zero at X0, see shrinkage_strain).
  const bool deforming = s.elastic && deform;
  if (deforming) {
    start = std::chrono::steady_clock::now();
    tet_moisture_into(model, state, x_tet);
    parallel_for_chunks(0, mesh.tet_count(), [&](std::size_t lo, std::size_t hi) {
      for (std::size_t t = lo; t < hi; ++t)
        s.strain[t] = model.tet_active[t] ? shrinkage_strain(volume_ratio(tissue, x_tet[t])) : 0.0;
    });
    s.elastic->set_tet_shrinkage_strain(s.strain);
    ElasticState elastic{std::move(state.positions), std::move(state.velocities)};
    if (model.settings.quasi_static) {
      report.deformation_iterations = s.elastic->solve_quasi_static(elastic);
    } else {
      s.elastic->step(elastic, dt_s);
    }
    report.deformation_cg_iterations = s.elastic->last_cg_iterations();
    state.positions = std::move(elastic.positions);
    state.velocities = std::move(elastic.velocities);
    report.seconds_deformation = seconds_since(start);
  }
  // Without a deformation the shape is the one whose flesh tets were all checked positive above.
  report.inverted_tets = deforming ? inverted_tet_count(mesh, state.positions) : 0;
  state.time_s += dt_s;
  ++state.step_count;
  return report;
}

// Checkpoint: "FSDESIC1", u32 version 1, f64 time_s, i64 step_count, f64 evaporated_kg, u64 #V, then #V f64
// moisture, 3 #V f64 positions, 3 #V f64 velocities (little-endian host order).
namespace {
constexpr char checkpoint_magic[8] = {'F', 'S', 'D', 'E', 'S', 'I', 'C', '1'};
constexpr std::size_t checkpoint_header = 8 + 4 + 8 + 8 + 8 + 8;

}  // namespace

std::string desiccation_checkpoint_bytes(const DesiccationState& state) {
  const std::size_t n = state.node_moisture.size();
  std::string out;
  out.reserve(checkpoint_header + n * 7 * sizeof(double));
  out.append(checkpoint_magic, 8);
  bytes::append<std::uint32_t>(out, 1);
  bytes::append<double>(out, state.time_s);
  bytes::append<std::int64_t>(out, state.step_count);
  bytes::append<double>(out, state.evaporated_kg);
  bytes::append<std::uint64_t>(out, n);
  for (double x : state.node_moisture) bytes::append<double>(out, x);
  for (const std::vector<Vec3>* field : {&state.positions, &state.velocities}) {
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 p = i < field->size() ? (*field)[i] : Vec3::Zero();
      for (int k = 0; k < 3; ++k) bytes::append<double>(out, p[k]);
    }
  }
  return out;
}

void write_desiccation_checkpoint(const std::filesystem::path& path, const DesiccationState& state) {
  write_file_atomic(path, desiccation_checkpoint_bytes(state));
}

DesiccationState read_desiccation_checkpoint(const std::filesystem::path& path, std::size_t vertex_count) {
  return desiccation_state_from_bytes(read_file(path, checkpoint_header + (vertex_count * 7 + 1) * sizeof(double)),
                                      vertex_count, path.string());
}

DesiccationState desiccation_state_from_bytes(const std::string& in, std::size_t vertex_count,
                                              const std::string& source) {
  require_input(in.size() >= checkpoint_header, source, "byte 0", "too short for a desiccation checkpoint");
  require_input(std::memcmp(in.data(), checkpoint_magic, 8) == 0, source, "byte 0", "not a desiccation checkpoint");
  std::size_t offset = 8;
  const auto version = bytes::read<std::uint32_t>(in, offset);
  require_input(version == 1, source, "byte 8", "unknown checkpoint version " + std::to_string(version));
  DesiccationState state;
  state.time_s = bytes::read<double>(in, offset);
  state.step_count = bytes::read<std::int64_t>(in, offset);
  state.evaporated_kg = bytes::read<double>(in, offset);
  const auto n = bytes::read<std::uint64_t>(in, offset);
  require_input(n == vertex_count, source, "byte 36",
                "checkpoint has " + std::to_string(n) + " nodes, the model " + std::to_string(vertex_count));
  require_input(in.size() == checkpoint_header + n * 7 * sizeof(double), source, "byte " + std::to_string(in.size()),
                "file size does not match the node count");
  require_input(std::isfinite(state.time_s) && state.time_s >= 0.0 && state.step_count >= 0, source, "byte 12",
                "bad time or step count");
  state.node_moisture.resize(n);
  for (double& x : state.node_moisture) x = bytes::read<double>(in, offset);
  bytes::read_points(in, offset, n, state.positions);
  bytes::read_points(in, offset, n, state.velocities);
  for (std::size_t i = 0; i < n; ++i)
    require_input(
        std::isfinite(state.node_moisture[i]) && state.positions[i].allFinite() && state.velocities[i].allFinite(),
        source, "node " + std::to_string(i), "non-finite value");
  return state;
}

}  // namespace forensim
