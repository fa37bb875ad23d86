#include <gtest/gtest.h>

#include <cmath>

#include "analytic_slab.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fem/diffusion_solver.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_boundary.hpp"

using namespace forensim;

namespace {

Vec3 centroid(const TetMesh& mesh, std::size_t t) {
  Vec3 c = Vec3::Zero();
  for (Index n : mesh.tets[t]) c += mesh.positions[static_cast<std::size_t>(n)] / 4.0;
  return c;
}

/// Per-tet coefficient varying smoothly over the box (to exercise non-uniform assembly).
std::vector<double> varying(const TetMesh& mesh, double base, double amplitude) {
  std::vector<double> v(mesh.tet_count());
  for (std::size_t t = 0; t < v.size(); ++t) {
    const Vec3 c = centroid(mesh, t);
    v[t] = base * (1.0 + amplitude * std::sin(1.3 * c.x() + 0.7 * c.y() - 0.4 * c.z()));
  }
  return v;
}

std::vector<double> initial_field(const TetMesh& mesh) {
  std::vector<double> u(mesh.vertex_count());
  for (std::size_t n = 0; n < u.size(); ++n) {
    const Vec3& p = mesh.positions[n];
    u[n] = 0.8 + 0.1 * std::cos(p.x()) * std::sin(2 * p.y() + p.z());
  }
  return u;
}

}  // namespace

TEST(DiffusionSolver, SlabMatchesSeriesSolution) {
  // Bi = 2, to Fourier number 0.1, 20 cells, 100 steps.
  const double error = test::slab_error(20, 100, 2.0, 0.1, true);
  EXPECT_LT(error, 5e-3);
  EXPECT_LT(test::slab_error(20, 100, 2.0, 0.1, false), 5e-3);
}

TEST(DiffusionSolver, EquilibriumStaysPut) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(3, 2, 2), 3, 2, 2);
  const auto active = diffusion_active_tets(mesh);
  DiffusionSolver solver(mesh, active, skin_robin_faces(mesh, active, 1e-6, 0.4));
  std::vector<double> u(mesh.vertex_count(), 0.4);
  for (int s = 0; s < 3; ++s) solver.step(u, 500.0);
  for (double v : u) EXPECT_NEAR(v, 0.4, 1e-12);
}

class DiffusionMassBalance : public ::testing::TestWithParam<std::tuple<bool, SparseSolverKind>> {};

TEST_P(DiffusionMassBalance, ContentLostEqualsBoundaryOutflow) {
  const auto [lumped, kind] = GetParam();
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(3, 2, 2), 5, 4, 4);
  const auto active = diffusion_active_tets(mesh);
  std::vector<RobinFace> faces = skin_robin_faces(mesh, active, 2e-6, 0.1);
  DiffusionSettings settings;
  settings.lumped_mass = lumped;
  settings.solver = kind;
  DiffusionSolver solver(mesh, active, faces, settings);
  std::vector<double> cover(faces.size());
  for (std::size_t k = 0; k < cover.size(); ++k) cover[k] = (k % 3 == 0) ? 0.2 : 1.0;  // partly clothed
  solver.set_face_cover(cover);
  std::vector<double> u = initial_field(mesh);
  double outflow_total = 0.0;
  double storage_total = 0.0;
  const double start = [&] {
    solver.set_tet_capacity(varying(mesh, 1000.0, 0.3));
    return solver.total_content(u);
  }();
  double content = start;
  for (int s = 0; s < 6; ++s) {
    // Coefficients change every step, as moisture-dependent laws do (eqs. 7, 8).
    solver.set_tet_diffusivity(varying(mesh, 1e-9 * (1.0 + 0.2 * s), 0.5));
    solver.set_tet_capacity(varying(mesh, 1000.0 * (1.0 - 0.02 * s), 0.3));
    const double before = solver.total_content(u);
    const DiffusionStepReport r = solver.step(u, 200.0 + 50.0 * s);
    const double after = solver.total_content(u);
    EXPECT_TRUE(r.refactored);
    EXPECT_GT(r.boundary_outflow, 0.0);
    EXPECT_NEAR(after - before, r.storage_change, 1e-12 * before);
    EXPECT_NEAR(r.storage_change, -r.boundary_outflow, 1e-10 * before) << "step " << s;
    outflow_total += r.boundary_outflow;
    storage_total += r.storage_change;
    content = after;
  }
  EXPECT_NEAR(storage_total, -outflow_total, 1e-10 * start);
  EXPECT_LT(content, start);
}

INSTANTIATE_TEST_SUITE_P(Variants, DiffusionMassBalance,
                         ::testing::Values(std::make_tuple(true, SparseSolverKind::cholmod),
                                           std::make_tuple(false, SparseSolverKind::cholmod),
                                           std::make_tuple(true, SparseSolverKind::cg_incomplete_cholesky),
                                           std::make_tuple(false, SparseSolverKind::cg_jacobi)));

TEST(DiffusionSolver, UnchangedCoefficientsReuseTheFactorisation) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 2, 2), 2, 2, 2);
  DiffusionSolver solver(mesh, {}, skin_robin_faces(mesh, {}, 1e-6, 0.0));
  std::vector<double> u(mesh.vertex_count(), 1.0);
  EXPECT_TRUE(solver.step(u, 100.0).refactored);
  EXPECT_FALSE(solver.step(u, 100.0).refactored);
  EXPECT_TRUE(solver.step(u, 50.0).refactored);
  solver.set_tet_diffusivity(std::vector<double>(mesh.tet_count(), 2e-9));
  EXPECT_TRUE(solver.step(u, 50.0).refactored);
}

TEST(DiffusionSolver, SealedSurfaceLosesNothing) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 2, 2), 3, 3, 3);
  auto faces = skin_robin_faces(mesh, {}, 1e-5, 0.0);
  DiffusionSolver solver(mesh, {}, faces);
  solver.set_face_cover(std::vector<double>(faces.size(), 0.0));
  std::vector<double> u = initial_field(mesh);
  const double before = solver.total_content(u);
  const auto r = solver.step(u, 1000.0);
  EXPECT_EQ(r.boundary_outflow, 0.0);
  EXPECT_NEAR(solver.total_content(u), before, 1e-12 * before);
}

TEST(DiffusionSolver, BoneHoldsNoWaterAndIsNoSink) {
  // Box [0,2]x[0,1]x[0,1]: bone where x < 0.8, flesh elsewhere; the skin is the flesh's outer surface.
  TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 1, 1), 10, 4, 4);
  mesh.tet_labels.resize(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    mesh.tet_labels[t] = centroid(mesh, t).x() < 0.8 ? tissue_bone : tissue_flesh;
  }
  const auto active = diffusion_active_tets(mesh);
  const auto faces = skin_robin_faces(mesh, active, 3e-6, 0.0);
  DiffusionSolver solver(mesh, active, faces);
  std::vector<double> u = initial_field(mesh);
  std::vector<Index> bone_only;
  for (std::size_t n = 0; n < u.size(); ++n) {
    if (!solver.node_active(static_cast<Index>(n))) {
      u[n] = 0.3;
      bone_only.push_back(static_cast<Index>(n));
    }
  }
  ASSERT_FALSE(bone_only.empty());
  // The same flesh as a mesh of its own: the bone must change nothing.
  TetMesh flesh = mesh;
  flesh.tets.clear();
  flesh.tet_labels.clear();
  std::vector<Index> flesh_tet(mesh.tet_count(), -1);
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (active[t] == 0) continue;
    flesh_tet[t] = static_cast<Index>(flesh.tets.size());
    flesh.tets.push_back(mesh.tets[t]);
  }
  std::vector<RobinFace> flesh_faces = faces;  // the same skin (not the cut face towards the bone)
  for (RobinFace& f : flesh_faces) f.tet = flesh_tet[static_cast<std::size_t>(f.tet)];
  DiffusionSolver flesh_solver(flesh, {}, flesh_faces);
  std::vector<double> v = u;
  for (int s = 0; s < 5; ++s) {
    const double before = solver.total_content(u);
    const auto r = solver.step(u, 2000.0);
    flesh_solver.step(v, 2000.0);
    // No flux across the bone interface: the flesh loses exactly what leaves through the skin.
    EXPECT_NEAR(solver.total_content(u) - before, -r.boundary_outflow, 1e-10 * before);
  }
  for (Index n : bone_only) EXPECT_EQ(u[static_cast<std::size_t>(n)], 0.3);
  for (std::size_t n = 0; n < u.size(); ++n) EXPECT_NEAR(u[n], v[n], 1e-12);
  // The interface nodes kept more water than the skin nodes (they are insulated, not drained).
  double interface_mean = 0.0, skin_mean = 0.0;
  int interface_count = 0, skin_count = 0;
  for (std::size_t n = 0; n < u.size(); ++n) {
    const double x = mesh.positions[n].x();
    if (std::abs(x - 0.8) < 1e-9 && mesh.positions[n].y() > 0.1 && mesh.positions[n].y() < 0.9 &&
        mesh.positions[n].z() > 0.1 && mesh.positions[n].z() < 0.9) {
      interface_mean += u[n];
      ++interface_count;
    }
    if (std::abs(x - 2.0) < 1e-9) {
      skin_mean += u[n];
      ++skin_count;
    }
  }
  ASSERT_GT(interface_count, 0);
  EXPECT_GT(interface_mean / interface_count, skin_mean / skin_count);
}

TEST(DiffusionSolver, SameResultAtOneAndTwoThreads) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(3, 2, 2), 6, 5, 5);
  auto run = [&](int threads) {
    set_thread_count(threads);
    DiffusionSolver solver(mesh, {}, skin_robin_faces(mesh, {}, 2e-6, 0.1));
    solver.set_tet_diffusivity(varying(mesh, 1e-9, 0.5));
    solver.set_tet_capacity(varying(mesh, 1000.0, 0.3));
    std::vector<double> u = initial_field(mesh);
    for (int s = 0; s < 3; ++s) solver.step(u, 300.0);
    set_thread_count(0);
    return u;
  };
  const auto a = run(1);
  const auto b = run(2);
  for (std::size_t n = 0; n < a.size(); ++n) ASSERT_EQ(a[n], b[n]);
}

TEST(DiffusionSolver, RejectsBadInput) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3::Ones(), 1, 1, 1);
  EXPECT_THROW(DiffusionSolver(mesh, std::vector<std::uint8_t>(3, 1), {}), InputError);
  std::vector<RobinFace> bad = {RobinFace{{0, 1, 2}, 99, 1e-6, 0.0, 1.0}};
  EXPECT_THROW(DiffusionSolver(mesh, {}, bad), InputError);
  DiffusionSolver solver(mesh, {}, {});
  std::vector<double> u(mesh.vertex_count(), 1.0);
  EXPECT_THROW(solver.step(u, -1.0), InputError);
  EXPECT_THROW(solver.set_tet_diffusivity({1.0}), InputError);
}

TEST(DiffusionSolver, OneCallFormBalancesItsOutflow) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 2, 2), 3, 3, 3);
  const auto faces = skin_robin_faces(mesh, {}, 1e-6, 0.0);
  std::vector<double> u(mesh.vertex_count(), 1.0);
  const double before = 8.0;  // content of u = 1, c = 1 over 8 mm^3
  const double outflow = diffuse(mesh, faces, 1e-9, 600.0, 4, u);
  DiffusionSolver probe(mesh, {}, faces);
  EXPECT_GT(outflow, 0.0);
  EXPECT_NEAR(probe.total_content(u), before - outflow, 1e-10 * before);
}

TEST(DiffusionSolver, AllBoneIsANoOp) {
  TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3::Ones(), 2, 2, 2);
  mesh.tet_labels.assign(mesh.tet_count(), tissue_bone);
  const auto active = diffusion_active_tets(mesh);
  DiffusionSolver solver(mesh, active, skin_robin_faces(mesh, active, 1e-6, 0.0));
  EXPECT_EQ(solver.active_node_count(), 0u);
  std::vector<double> u(mesh.vertex_count(), 0.25);
  EXPECT_EQ(solver.step(u, 100.0).boundary_outflow, 0.0);
  for (double v : u) EXPECT_EQ(v, 0.25);
}
