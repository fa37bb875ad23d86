// Cost of one desiccation step on the `paper` arm (make_phantom_model(phantom_model_size("arm", "paper")),
// about 29k nodes and 141k tets, as Table 1 of Frerichs, Vidler and Gatzidis 2020), beside the paper's
// Table 2 (arm on an i7 at 3.4 GHz: 0.372 s per implicit dehydration step, 2.563 s per volume deformation
// step). BM_DehydrationStep: one moisture step (coefficients from the current moisture and shape, reassembly,
// warm-started CG). BM_DeformationStep: one quasi-static volume deformation under the shrinkage of a dried
// state (from the rest shape each iteration, so every run does the same work) and one dynamic implicit step.
// The model is built once (about 25 s). Timings are wall-clock (UseRealTime).
#include <benchmark/benchmark.h>

#include <memory>

#include "body/phantom_model.hpp"
#include "desiccation/desiccation_sim.hpp"

using namespace forensim;

namespace {

constexpr double hour = 3600.0;

const DesiccationModel& paper_arm(bool quasi_static) {
  static const BodyModel body = make_phantom_model(phantom_model_size("arm", "paper"));
  static std::unique_ptr<DesiccationModel> models[2];
  auto& m = models[quasi_static ? 1 : 0];
  if (!m) {
    DesiccationSettings settings;
    settings.quasi_static = quasi_static;
    m = std::make_unique<DesiccationModel>(make_desiccation_model(body, settings));
  }
  return *m;
}

/// A state a few days into the run (moisture gradients near the skin), computed once.
const DesiccationState& dried_state() {
  static const DesiccationState state = [] {
    DesiccationSettings settings;
    settings.deform = false;
    static const DesiccationModel model = make_desiccation_model(paper_arm(true).body, settings);
    DesiccationState s = initial_desiccation_state(model);
    DesiccationSolver solver(model);
    for (int i = 0; i < 6; ++i) solver.step(s, 12 * hour);
    return s;
  }();
  return state;
}

void BM_DehydrationStep(benchmark::State& bench) {
  DesiccationSettings settings;
  settings.deform = false;
  static const DesiccationModel model = make_desiccation_model(paper_arm(true).body, settings);
  DesiccationSolver solver(model);
  DesiccationState state = dried_state();
  for (auto _ : bench) {
    const DesiccationStepReport r = solver.step(state, hour);
    benchmark::DoNotOptimize(r.evaporated_kg);
    bench.counters["cg_iterations"] = r.diffusion_iterations;
  }
  bench.counters["nodes"] = static_cast<double>(model.body.volume.vertex_count());
  bench.counters["tets"] = static_cast<double>(model.body.volume.tet_count());
  bench.counters["paper_s"] = 0.372;
}
BENCHMARK(BM_DehydrationStep)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

void BM_DeformationStep(benchmark::State& bench) {
  const bool quasi_static = bench.range(0) == 1;
  const DesiccationModel& model = paper_arm(quasi_static);
  DesiccationSolver solver(model);
  const DesiccationState dried = dried_state();
  for (auto _ : bench) {
    bench.PauseTiming();
    DesiccationState state = initial_desiccation_state(model);
    state.node_moisture = dried.node_moisture;
    bench.ResumeTiming();
    // The moisture part of a step is BM_DehydrationStep; here it is a tiny step so that the deformation
    // dominates (its time is reported apart in the counters).
    const DesiccationStepReport r = solver.step(state, 1.0);
    bench.counters["deformation_s"] = r.seconds_deformation;
    bench.counters["iterations"] = r.deformation_iterations;
  }
  bench.counters["paper_s"] = 2.563;
}
BENCHMARK(BM_DeformationStep)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
