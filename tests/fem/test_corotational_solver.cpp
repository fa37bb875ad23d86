#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fem/corotational_solver.hpp"
#include "fem/tet_element.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

const ElasticMaterial flesh{1e4, 0.3, 1050.0};
const ElasticMaterial bone{1e9, 0.3, 1900.0};

double volume_of(const TetMesh& mesh, const std::vector<Vec3>& x, int label = -1) {
  double v = 0.0;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (label >= 0 && mesh.label(t) != label) continue;
    const Tet& e = mesh.tets[t];
    v += tet_volume({x[static_cast<std::size_t>(e[0])], x[static_cast<std::size_t>(e[1])],
                     x[static_cast<std::size_t>(e[2])], x[static_cast<std::size_t>(e[3])]});
  }
  return v;
}

Vec3 centroid(const TetMesh& mesh, std::size_t t) {
  Vec3 c = Vec3::Zero();
  for (Index n : mesh.tets[t]) c += mesh.positions[static_cast<std::size_t>(n)] / 4.0;
  return c;
}

TetMesh cube_with_bone(int n) {
  TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 1, 1), 2 * n, n, n);
  mesh.tet_labels.resize(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    mesh.tet_labels[t] = centroid(mesh, t).x() < 0.5 ? tissue_bone : tissue_flesh;
  }
  return mesh;
}

/// Central differences of solver.elastic_energy at x against solver.elastic_forces (relative to the largest force).
void expect_forces_are_minus_energy_gradient(const CorotationalSolver& solver, const std::vector<Vec3>& x, double step,
                                             double tolerance) {
  const auto f = solver.elastic_forces(x);
  double scale = 0.0;
  for (const Vec3& v : f) scale = std::max(scale, v.norm());
  for (std::size_t n = 0; n < x.size(); ++n) {
    for (int c = 0; c < 3; ++c) {
      std::vector<Vec3> plus = x, minus = x;
      plus[n][c] += step;
      minus[n][c] -= step;
      const double fd = -(solver.elastic_energy(plus) - solver.elastic_energy(minus)) / (2 * step);
      EXPECT_NEAR(f[n][c], fd, tolerance * scale) << "node " << n << " axis " << c;
    }
  }
}

}  // namespace

TEST(CorotationalSolver, ShrinkageStrainGivesVolumeRatio) {
  EXPECT_EQ(shrinkage_strain(1.0), 0.0);
  EXPECT_NEAR(std::pow(1.0 + shrinkage_strain(0.6), 3), 0.6, 1e-15);
  EXPECT_THROW(shrinkage_strain(0.0), InputError);
}

TEST(CorotationalSolver, FreeCubeShrinksToExactVolumeRatio) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 2, 2), 4, 4, 4);
  const double sv = 0.7;
  for (double angle : {0.0, 2.2}) {
    CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone));
    solver.set_tet_shrinkage_strain(std::vector<double>(mesh.tet_count(), shrinkage_strain(sv)));
    ElasticState state = solver.rest_state();
    // Start rigidly rotated and moved: shrinkage must not depend on the body's orientation.
    const Mat3 q = Eigen::AngleAxisd(angle, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
    for (Vec3& p : state.positions) p = q * p + Vec3(5, 0, -3);
    const int iterations = solver.solve_quasi_static(state);
    EXPECT_LT(iterations, 20);
    const double v0 = volume_of(mesh, mesh.positions);
    EXPECT_NEAR(volume_of(mesh, state.positions) / v0, sv, 1e-6) << "angle " << angle;
    // Uniform shrinkage: every distance scales by (1 + s).
    const double scale = 1.0 + shrinkage_strain(sv);
    const std::size_t last = mesh.vertex_count() - 1;
    EXPECT_NEAR((state.positions[last] - state.positions[0]).norm(),
                scale * (mesh.positions[last] - mesh.positions[0]).norm(), 1e-6);
  }
}

TEST(CorotationalSolver, NoForceUnderRigidMotion) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 1, 1), 3, 2, 2);
  CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone));
  const Mat3 q = Eigen::AngleAxisd(1.1, Vec3(0.2, 1, 0.3).normalized()).toRotationMatrix();
  std::vector<Vec3> x = mesh.positions;
  for (Vec3& p : x) p = q * p + Vec3(1, 2, 3);
  double largest = 0.0;
  for (const Vec3& f : solver.elastic_forces(x)) largest = std::max(largest, f.norm());
  EXPECT_LT(largest, 1e-12);
  EXPECT_NEAR(solver.elastic_energy(x), 0.0, 1e-15);
}

TEST(CorotationalSolver, ForcesAreMinusEnergyGradient) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 1, 1), 2, 1, 1);
  CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone));
  std::vector<double> strain(mesh.tet_count());
  for (std::size_t t = 0; t < strain.size(); ++t) strain[t] = -0.05 - 0.01 * static_cast<double>(t % 4);
  solver.set_tet_shrinkage_strain(strain);
  std::vector<Vec3> x = mesh.positions;
  const Mat3 q = Eigen::AngleAxisd(0.4, Vec3(1, 1, 1).normalized()).toRotationMatrix();
  for (std::size_t n = 0; n < x.size(); ++n) {
    x[n] = q * x[n] + 0.03 * Vec3(std::sin(1.0 * n), std::cos(2.0 * n), std::sin(3.0 * n + 1));
  }
  expect_forces_are_minus_energy_gradient(solver, x, 1e-6, 1e-6);
}

TEST(CorotationalSolver, AnchoredBoneKeepsItsShape) {
  const TetMesh mesh = cube_with_bone(3);
  CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone));
  solver.set_tet_shrinkage_strain(std::vector<double>(mesh.tet_count(), shrinkage_strain(0.6)));
  ElasticState state = solver.rest_state();
  solver.solve_quasi_static(state);
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (mesh.label(t) != tissue_bone) continue;
    for (Index n : mesh.tets[t]) {
      EXPECT_TRUE(solver.node_fixed(n));
      EXPECT_EQ(state.positions[static_cast<std::size_t>(n)], mesh.positions[static_cast<std::size_t>(n)]);
    }
  }
  EXPECT_EQ(volume_of(mesh, state.positions, tissue_bone), volume_of(mesh, mesh.positions, tissue_bone));
  // The flesh, held by the bone on one side, still shrinks (though less than when free).
  const double ratio = volume_of(mesh, state.positions, tissue_flesh) / volume_of(mesh, mesh.positions, tissue_flesh);
  EXPECT_LT(ratio, 0.85);
  EXPECT_GT(ratio, 0.6);
}

TEST(CorotationalSolver, StiffBoneBarelyDeforms) {
  const TetMesh mesh = cube_with_bone(3);
  CorotationalSettings settings;
  settings.rigid_mode = RigidMode::stiff;
  settings.rigid_stiffness_factor = 1.0;  // bone's own E = 1 GPa is 1e5 x flesh
  CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone), settings);
  solver.set_tet_shrinkage_strain(std::vector<double>(mesh.tet_count(), shrinkage_strain(0.6)));
  ElasticState state = solver.rest_state();
  solver.solve_quasi_static(state);
  const double bone_ratio =
      volume_of(mesh, state.positions, tissue_bone) / volume_of(mesh, mesh.positions, tissue_bone);
  EXPECT_NEAR(bone_ratio, 1.0, 1e-4);
  const double flesh_ratio =
      volume_of(mesh, state.positions, tissue_flesh) / volume_of(mesh, mesh.positions, tissue_flesh);
  EXPECT_LT(flesh_ratio, 0.85);
}

TEST(CorotationalSolver, DynamicStepsConserveMomentumAndSettle) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 2, 2), 3, 3, 3);
  CorotationalSettings settings;
  settings.rayleigh_alpha = 10.0;
  settings.rayleigh_beta = 1e-4;
  CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone), settings);
  solver.set_tet_shrinkage_strain(std::vector<double>(mesh.tet_count(), shrinkage_strain(0.8)));
  ElasticState state = solver.rest_state();
  const auto mass = solver.node_masses_kg();
  double total_mass = 0.0;
  for (double m : mass) total_mass += m;
  double top_speed = 0.0;
  for (int s = 0; s < 60; ++s) {
    solver.step(state, 2e-3);
    // Internal forces sum to zero: no external force, no momentum.
    Vec3 momentum = Vec3::Zero();
    for (std::size_t n = 0; n < mass.size(); ++n) {
      momentum += mass[n] * state.velocities[n];
      top_speed = std::max(top_speed, state.velocities[n].norm());
    }
    EXPECT_LT(momentum.norm(), 1e-9 * total_mass * top_speed);
  }
  EXPECT_GT(top_speed, 1.0);  // mm/s: it did move
  EXPECT_NEAR(volume_of(mesh, state.positions) / volume_of(mesh, mesh.positions), 0.8, 1e-4);
}

TEST(CorotationalSolver, FixedNodesStayAndResultsAreThreadIndependent) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 1, 1), 4, 2, 2);
  std::vector<Index> left;
  for (std::size_t n = 0; n < mesh.vertex_count(); ++n) {
    if (mesh.positions[n].x() < 1e-9) left.push_back(static_cast<Index>(n));
  }
  auto run = [&](int threads) {
    set_thread_count(threads);
    CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone));
    solver.set_fixed_nodes(left);
    std::vector<double> strain(mesh.tet_count());
    for (std::size_t t = 0; t < strain.size(); ++t) strain[t] = -0.1 * centroid(mesh, t).x();
    solver.set_tet_shrinkage_strain(strain);
    std::vector<Vec3> gravity(mesh.vertex_count(), Vec3(0, 0, -1e-6));
    solver.set_external_forces(gravity);
    ElasticState state = solver.rest_state();
    solver.solve_quasi_static(state);
    solver.step(state, 1e-3);
    set_thread_count(0);
    return state.positions;
  };
  const auto a = run(1);
  const auto b = run(2);
  for (std::size_t n = 0; n < a.size(); ++n) ASSERT_EQ(a[n], b[n]);
  for (Index n : left) EXPECT_EQ(a[static_cast<std::size_t>(n)], mesh.positions[static_cast<std::size_t>(n)]);
}

TEST(CorotationalSolver, RejectsBadMaterials) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3::Ones(), 1, 1, 1);
  ElasticMaterials m = elastic_materials_from_labels(mesh, flesh, bone);
  m.tet_poisson_ratio[2] = 0.5;
  EXPECT_THROW(CorotationalSolver(mesh, m), InputError);
  m = elastic_materials_from_labels(mesh, flesh, bone);
  m.tet_density_kg_per_m3.pop_back();
  EXPECT_THROW(CorotationalSolver(mesh, m), InputError);
}

TEST(CorotationalSolver, OneCallFormShrinksFreeBody) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(1, 1, 1), 2, 2, 2);
  const auto x = shrink_quasi_static(mesh, elastic_materials_from_labels(mesh, flesh, bone),
                                     std::vector<double>(mesh.tet_count(), 0.5));
  EXPECT_NEAR(volume_of(mesh, x), 0.5, 1e-6);
}

TEST(CorotationalSolver, NodesOfNoTetStayPut) {
  TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(1, 1, 1), 2, 2, 2);
  mesh.positions.push_back(Vec3(5, 5, 5));  // a stray node
  CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone));
  solver.set_tet_shrinkage_strain(std::vector<double>(mesh.tet_count(), shrinkage_strain(0.8)));
  ElasticState state = solver.rest_state();
  for (int s = 0; s < 3; ++s) solver.step(state, 1e-3);
  EXPECT_TRUE(solver.node_fixed(static_cast<Index>(mesh.vertex_count() - 1)));
  EXPECT_EQ(state.positions.back(), Vec3(5, 5, 5));
  EXPECT_LT(volume_of(mesh, state.positions), 1.0);
}

TEST(CorotationalSolver, BarrierForcesAreMinusEnergyGradient) {
  // Squeezed to an eighth of the volume while the eigenstrain aims at 0.86: inside the compression barrier.
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(2, 1, 1), 2, 1, 1);
  CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone));
  solver.set_tet_shrinkage_strain(std::vector<double>(mesh.tet_count(), -0.05));
  std::vector<Vec3> x = mesh.positions;
  for (std::size_t n = 0; n < x.size(); ++n) {
    x[n] = 0.5 * x[n] + 0.01 * Vec3(std::sin(1.0 * n), std::cos(2.0 * n), std::sin(3.0 * n + 1));
  }
  CorotationalSettings off;
  off.volume_barrier_ratio = 0.0;
  CorotationalSolver plain(mesh, elastic_materials_from_labels(mesh, flesh, bone), off);
  plain.set_tet_shrinkage_strain(std::vector<double>(mesh.tet_count(), -0.05));
  EXPECT_GT(solver.elastic_energy(x), plain.elastic_energy(x));  // the barrier acts
  expect_forces_are_minus_energy_gradient(solver, x, 1e-7, 1e-5);
}

TEST(CorotationalSolver, LaterallyHeldSlabShrinksWithoutTurningOver) {
  // A thin slab held at its rim and dried to 5 % of its volume: it can only thin, and the corotated linear
  // model alone puts its equilibrium thickness below zero (1 + s (1 + 2 nu / (1 - nu)) < 0 for s = -0.63), so
  // its tets turn over. With the compression barrier none does, and each keeps some volume.
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3(4, 4, 0.5), 8, 8, 1);
  std::vector<Index> rim;
  for (std::size_t n = 0; n < mesh.vertex_count(); ++n) {
    const Vec3& p = mesh.positions[n];
    if (p.x() < 1e-9 || p.y() < 1e-9 || p.x() > 4 - 1e-9 || p.y() > 4 - 1e-9) rim.push_back(static_cast<Index>(n));
  }
  const double strain = shrinkage_strain(0.05);
  auto smallest_volume_ratio = [&](double barrier) {
    CorotationalSettings settings;
    settings.volume_barrier_ratio = barrier;
    settings.quasi_static_max_iterations = 60;
    CorotationalSolver solver(mesh, elastic_materials_from_labels(mesh, flesh, bone), settings);
    solver.set_fixed_nodes(rim);
    solver.set_tet_shrinkage_strain(std::vector<double>(mesh.tet_count(), strain));
    ElasticState state = solver.rest_state();
    solver.solve_quasi_static(state);
    double smallest = 1e300;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
      TetCorners a, b;
      for (int k = 0; k < 4; ++k) {
        a[k] = mesh.positions[static_cast<std::size_t>(mesh.tets[t][k])];
        b[k] = state.positions[static_cast<std::size_t>(mesh.tets[t][k])];
      }
      smallest = std::min(smallest, tet_volume(b) / tet_volume(a));
    }
    return smallest;
  };
  EXPECT_LT(smallest_volume_ratio(0.0), 0.0);  // without the barrier: turned over
  const double with_barrier = smallest_volume_ratio(0.5);
  EXPECT_GT(with_barrier, 0.0);
  EXPECT_LT(with_barrier, 0.05);  // still squeezed below its target: the rim holds it
}
