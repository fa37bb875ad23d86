// Cost of forensim's FEM layer on a ~30k-node tet mesh (a 30^3-cell Kuhn box: 29,791 nodes, 162,000 tets,
// 10 x 10 x 10 cm): sparsity pattern set-up, parallel assembly (scalar 4x4 and 3x3-block 12x12), sparse
// factorisation and solves per backend, and one moisture-diffusion step and one corotational step per
// backend. The "refactor" diffusion step changes the coefficients first, as the desiccation laws do every
// step (eqs. 7, 8); "same" reuses the factorisation. Timings are wall-clock (UseRealTime).
#include <benchmark/benchmark.h>

#include <vector>

#include "fem/corotational_solver.hpp"
#include "fem/diffusion_solver.hpp"
#include "fem/sparse_assembly.hpp"
#include "fem/sparse_solver.hpp"
#include "fem/tet_element.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

const TetMesh& mesh() {
  static const TetMesh m = make_box_tet_mesh(Vec3::Zero(), Vec3::Constant(100.0), 30, 30, 30);
  return m;
}

TetCorners corners(const TetMesh& m, std::size_t t) {
  const Tet& e = m.tets[t];
  return {m.positions[static_cast<std::size_t>(e[0])], m.positions[static_cast<std::size_t>(e[1])],
          m.positions[static_cast<std::size_t>(e[2])], m.positions[static_cast<std::size_t>(e[3])]};
}

const SparsityPattern& pattern(int block) {
  static const SparsityPattern scalar(mesh().tets, mesh().vertex_count(), 1);
  static const SparsityPattern blocks(mesh().tets, mesh().vertex_count(), 3);
  return block == 3 ? blocks : scalar;
}

void assemble_heat(SparseMatrix& a, double dt) {
  pattern(1).assemble_scalar(
      [&](std::size_t e, Mat4& m) {
        double volume = 0.0;
        const Mat34 g = tet_shape_gradients(corners(mesh(), e), &volume);
        m = tet_diffusion_stiffness(g, volume, dt * 1e-3) + tet_consistent_mass(volume, 1.0);
      },
      a);
}

void assemble_elastic(SparseMatrix& a) {
  pattern(3).assemble_block(
      [&](std::size_t e, Mat12& k) {
        double volume = 0.0;
        const Mat34 g = tet_shape_gradients(corners(mesh(), e), &volume);
        k = tet_linear_stiffness(g, volume, 10.0, 0.3);
        // Mass term of an implicit step keeps it definite without boundary conditions.
        k.diagonal().array() += 1e-3 * volume;
      },
      a);
}

SparseSolverKind kind_of(int i) {
  return static_cast<SparseSolverKind>(i);
}

void BM_PatternBuild(benchmark::State& state) {
  for (auto _ : state) {
    SparsityPattern p(mesh().tets, mesh().vertex_count(), static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(p.nonzero_count());
  }
}

void BM_AssembleScalar(benchmark::State& state) {
  SparseMatrix a = pattern(1).make_matrix();
  for (auto _ : state) assemble_heat(a, 1000.0);
  state.counters["nnz"] = static_cast<double>(a.nonZeros());
}

void BM_AssembleBlock(benchmark::State& state) {
  SparseMatrix a = pattern(3).make_matrix();
  for (auto _ : state) assemble_elastic(a);
  state.counters["nnz"] = static_cast<double>(a.nonZeros());
}

/// range(0): solver kind, range(1): block size (1 diffusion, 3 elasticity).
void BM_Factor(benchmark::State& state) {
  const int block = static_cast<int>(state.range(1));
  SparseMatrix a = pattern(block).make_matrix();
  block == 1 ? assemble_heat(a, 1000.0) : assemble_elastic(a);
  auto solver = make_sparse_solver(kind_of(static_cast<int>(state.range(0))), 1e-10);
  solver->analyse(a);
  for (auto _ : state) solver->factor(a);
}

void BM_Solve(benchmark::State& state) {
  const int block = static_cast<int>(state.range(1));
  SparseMatrix a = pattern(block).make_matrix();
  block == 1 ? assemble_heat(a, 1000.0) : assemble_elastic(a);
  auto solver = make_sparse_solver(kind_of(static_cast<int>(state.range(0))), 1e-10);
  solver->analyse(a);
  solver->factor(a);
  const Eigen::VectorXd b = a * Eigen::VectorXd::Ones(a.rows());
  // Warm start from a nearby vector, as from the previous time step.
  const Eigen::VectorXd guess = Eigen::VectorXd::Constant(a.rows(), 0.99);
  int iterations = 0;
  for (auto _ : state) {
    Eigen::VectorXd x = guess;
    solver->solve(b, x);
    iterations = solver->last_iterations();
  }
  state.counters["iterations"] = iterations;
}

/// range(0): solver kind, range(1): 1 = coefficients change every step (refactor), 0 = unchanged.
void BM_DiffusionStep(benchmark::State& state) {
  const TetMesh& m = mesh();
  DiffusionSettings settings;
  settings.solver = kind_of(static_cast<int>(state.range(0)));
  DiffusionSolver solver(m, {}, skin_robin_faces(m, {}, 1e-7, 0.1), settings);
  std::vector<double> u(m.vertex_count(), 1.0);
  std::vector<double> d(m.tet_count(), 1e-9);
  solver.set_tet_diffusivity(d);
  solver.step(u, 3600.0);
  int step = 0;
  DiffusionStepReport report;
  for (auto _ : state) {
    if (state.range(1) != 0) {
      d[static_cast<std::size_t>(step) % d.size()] *= 1.01;
      solver.set_tet_diffusivity(d);
    }
    report = solver.step(u, 3600.0);
    ++step;
  }
  state.counters["iterations"] = report.iterations;
}

/// range(0): preconditioner, 0 = rest stiffness factorised by CHOLMOD (once, before timing), 1 = Jacobi.
void BM_CorotationalStep(benchmark::State& state) {
  const TetMesh& m = mesh();
  CorotationalSettings settings;
  settings.preconditioner = state.range(0) == 0 ? ElasticPreconditioner::rest_cholesky : ElasticPreconditioner::jacobi;
  settings.rayleigh_alpha = 1.0;
  CorotationalSolver solver(m, elastic_materials_from_labels(m, ElasticMaterial{}, ElasticMaterial{}), settings);
  solver.set_tet_shrinkage_strain(std::vector<double>(m.tet_count(), shrinkage_strain(0.9)));
  ElasticState s = solver.rest_state();
  solver.step(s, 1e-2);
  for (auto _ : state) solver.step(s, 1e-2);
  state.counters["cg_iterations"] = solver.last_cg_iterations();
}

}  // namespace

BENCHMARK(BM_PatternBuild)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AssembleScalar)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AssembleBlock)->Unit(benchmark::kMillisecond)->UseRealTime();
// Kinds: 0 cholmod, 1 cg_ic, 2 cg_jacobi.
BENCHMARK(BM_Factor)
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({0, 3})
    ->Args({1, 3})
    ->Args({2, 3})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Solve)
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({0, 3})
    ->Args({1, 3})
    ->Args({2, 3})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_DiffusionStep)
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_CorotationalStep)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

BENCHMARK_MAIN();
