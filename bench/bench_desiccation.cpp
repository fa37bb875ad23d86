// Cost of one desiccation step on the `paper` arm (make_phantom_model(phantom_model_size("arm", "paper")),
// about 29k nodes and 145k tets, as Table 1 of Frerichs, Vidler and Gatzidis 2020), beside the paper's
// Table 2 (arm on an i7 at 3.4 GHz: 0.372 s per implicit dehydration step, 2.563 s per volume deformation
// step; forensim's goal is 30 times faster on 2 cores). `forensim bench desiccation` prints the same figures
// for the arm and the head beside the paper's.
//
// BM_DehydrationStep: one 1 h moisture step at day 3 (coefficients from the current moisture and shape,
// reassembly, warm-started CG). BM_ShapeUpdate: the quasi-static shape solve as `forensim mummify` does it by
// default (every 4th 12 h step): from the shape solved two days before, under the shrinkage of the moisture
// now; Arg(1) starts from the rest shape instead (a first solve). BM_DynamicStep: one implicit Euler step of
// 12 h (eq. 31) from the same state. Each iteration repeats the same work from the same state; the model is
// built once (about 25 s) and the one-off factorisation happens before timing. Wall-clock (UseRealTime).
#include <benchmark/benchmark.h>

#include <memory>

#include "body/phantom_model.hpp"
#include "desiccation/desiccation_sim.hpp"

using namespace forensim;

namespace {

constexpr double hour = 3600.0;

const BodyModel& paper_arm() {
  static const BodyModel body = make_phantom_model(phantom_model_size("arm", "paper"));
  return body;
}

const DesiccationModel& model(bool quasi_static) {
  static std::unique_ptr<DesiccationModel> models[2];
  auto& m = models[quasi_static ? 1 : 0];
  if (!m) {
    DesiccationSettings settings;
    settings.quasi_static = quasi_static;
    m = std::make_unique<DesiccationModel>(make_desiccation_model(paper_arm(), settings));
  }
  return *m;
}

DesiccationSolver& solver(bool quasi_static) {
  static std::unique_ptr<DesiccationSolver> solvers[2];
  auto& s = solvers[quasi_static ? 1 : 0];
  if (!s) s = std::make_unique<DesiccationSolver>(model(quasi_static));
  return *s;
}

/// Day 3 of a default run (6 moisture steps of 12 h), and day 5: the shape solved at day 3, then three more
/// moisture-only steps, as `forensim mummify` runs them (the fourth step solves the shape).
struct States {
  DesiccationState day3, day5;
};

const States& states() {
  static const States s = [] {
    States out;
    DesiccationSolver& sim = solver(true);
    DesiccationState state = initial_desiccation_state(model(true));
    for (int i = 0; i < 6; ++i) sim.step(state, 12 * hour, false);
    out.day3 = state;
    sim.step(state, 12 * hour, true);
    for (int i = 0; i < 3; ++i) sim.step(state, 12 * hour, false);
    out.day5 = state;
    return out;
  }();
  return s;
}

void BM_DehydrationStep(benchmark::State& bench) {
  DesiccationSolver& sim = solver(true);
  const DesiccationState& start = states().day3;
  DesiccationStepReport r;
  for (auto _ : bench) {
    bench.PauseTiming();
    DesiccationState state = start;
    bench.ResumeTiming();
    r = sim.step(state, hour, false);
    benchmark::DoNotOptimize(r.evaporated_kg);
  }
  bench.counters["cg_iterations"] = r.diffusion_iterations;
  bench.counters["nodes"] = static_cast<double>(model(true).body.volume.vertex_count());
  bench.counters["tets"] = static_cast<double>(model(true).body.volume.tet_count());
  bench.counters["paper_s"] = 0.372;
}
BENCHMARK(BM_DehydrationStep)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(10);

/// The deformation part of a 12 h step with the shape update (its moisture part is BM_DehydrationStep's
/// work; the reported time is the deformation alone, in the counter deformation_s and as manual time).
void BM_ShapeUpdate(benchmark::State& bench) {
  const bool from_rest = bench.range(0) == 1;
  DesiccationSolver& sim = solver(true);
  DesiccationState start = states().day5;
  if (from_rest) start.positions = model(true).body.volume.positions;
  DesiccationStepReport r;
  for (auto _ : bench) {
    DesiccationState state = start;
    r = sim.step(state, 12 * hour, true);
    bench.SetIterationTime(r.seconds_deformation);
  }
  bench.counters["newton_iterations"] = r.deformation_iterations;
  bench.counters["cg_iterations"] = r.deformation_cg_iterations;
  bench.counters["paper_s"] = 2.563;
}
BENCHMARK(BM_ShapeUpdate)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(5);

void BM_DynamicStep(benchmark::State& bench) {
  DesiccationSolver& sim = solver(false);
  const DesiccationState& start = states().day5;
  {
    DesiccationState warm = start;
    sim.step(warm, 12 * hour, true);  // factorisation for this dt
  }
  DesiccationStepReport r;
  for (auto _ : bench) {
    DesiccationState state = start;
    r = sim.step(state, 12 * hour, true);
    bench.SetIterationTime(r.seconds_deformation);
  }
  bench.counters["cg_iterations"] = r.deformation_cg_iterations;
  bench.counters["paper_s"] = 2.563;
}
BENCHMARK(BM_DynamicStep)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
