// `forensim bench desiccation`: the per-step cost of the desiccation system on the phantom arm and head at the
// chosen size (`paper`: Table 1 of Frerichs, Vidler and Gatzidis 2020), beside the paper's Table 2 (an i7 at
// 3.4 GHz) and forensim's goal of 30 times faster than the paper.
//
// What is timed, per phantom, in the default environment, each row the median of --repeat runs of the same
// work from the same state:
// - dehydration step: one implicit moisture step of 1 h (diffusivity and capacity from the current moisture
//   and shape, reassembly, warm-started CG) at day 3 of a run;
// - deformation, shape update: the quasi-static shape solve as `forensim mummify` does it by default (every
//   4th step of 12 h): from the shape solved two days before, under the shrinkage of the moisture now
//   (at day 5);
// - deformation, dynamic step: one implicit Euler step of 12 h (eq. 31) from the same state;
// - deformation, from rest: the same shape solve started from the undeformed body (the first solve of a
//   resumed or one-off run), for scale.
// The one-off set-up (pattern, CHOLMOD factorisation of the rest stiffness) is timed once and listed apart.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_registry.hpp"
#include "body/phantom_model.hpp"
#include "desiccation/desiccation_sim.hpp"

namespace forensim::cli {
namespace {

constexpr double hour = 3600.0;

struct PaperFigures {
  double dehydration_s, deformation_s;
};

void bench_phantom(const std::string& phantom, const BenchOptions& options, const PaperFigures& paper,
                   std::vector<BenchRow>& rows) {
  const std::string label = phantom + " " + options.size;
  const std::string ref = "Table 2, i7 3.4 GHz";
  auto start = std::chrono::steady_clock::now();
  const PhantomModelSize size = phantom_model_size(phantom, options.size);
  BodyModel body = make_phantom_model(size);
  const double seconds_model = seconds_since(start);
  const std::string counts =
      std::to_string(body.volume.vertex_count()) + " nodes, " + std::to_string(body.volume.tet_count()) + " tets";
  std::printf("  %s: %s (model built in %.1f s)\n", label.c_str(), counts.c_str(), seconds_model);
  std::fflush(stdout);

  const DesiccationModel model = make_desiccation_model(body, DesiccationSettings{});
  DesiccationSettings dynamic_settings;
  dynamic_settings.quasi_static = false;
  const DesiccationModel dynamic_model = make_desiccation_model(std::move(body), dynamic_settings);

  start = std::chrono::steady_clock::now();
  DesiccationSolver solver(model);
  DesiccationState state = initial_desiccation_state(model);
  DesiccationStepReport first = solver.step(state, 12 * hour, true);  // includes the one-off factorisation
  const double seconds_setup = seconds_since(start) - first.seconds_diffusion;
  // Day 3: moisture only (the shape is solved at day 3 below).
  for (int i = 1; i < 6; ++i) solver.step(state, 12 * hour, false);

  // Dehydration: a 1 h step from the day-3 state, repeated from the same state.
  std::vector<double> dehydration;
  int diffusion_iterations = 0;
  for (int r = 0; r < options.repetitions + 1; ++r) {
    DesiccationState s = state;
    const DesiccationStepReport report = solver.step(s, hour, false);
    diffusion_iterations = report.diffusion_iterations;
    if (r > 0) dehydration.push_back(report.seconds_diffusion);  // the first run warms caches
  }
  BenchTiming t = summarise_samples(dehydration);
  rows.push_back({label + ": dehydration step (1 h)", t.median_s, t.min_s, paper.dehydration_s, ref,
                  paper.dehydration_s / 30.0, std::to_string(diffusion_iterations) + " CG iterations; " + counts});

  // The shape at day 3, then four 12 h steps as mummify runs them: three moisture-only, the fourth with the
  // shape update (timed from the day-3 shape).
  const DesiccationStepReport cold = solver.step(state, 12 * hour, true);
  for (int i = 0; i < 3; ++i) solver.step(state, 12 * hour, false);
  std::vector<double> update;
  DesiccationStepReport last;
  for (int r = 0; r < options.repetitions; ++r) {
    DesiccationState s = state;
    last = solver.step(s, 12 * hour, true);
    update.push_back(last.seconds_deformation);
  }
  t = summarise_samples(update);
  rows.push_back({label + ": deformation, shape update (2 days)", t.median_s, t.min_s, paper.deformation_s, ref,
                  paper.deformation_s / 30.0,
                  std::to_string(last.deformation_iterations) + " Newton, " +
                      std::to_string(last.deformation_cg_iterations) + " CG iterations; tolerance " +
                      std::to_string(model.settings.elastic.quasi_static_tolerance_mm).substr(0, 5) + " mm"});

  // Dynamic implicit step (eq. 31) from the same state.
  DesiccationSolver dynamic_solver(dynamic_model);
  {
    DesiccationState s = state;
    dynamic_solver.step(s, 12 * hour, true);  // factorisation for this dt
  }
  std::vector<double> dynamic;
  for (int r = 0; r < options.repetitions; ++r) {
    DesiccationState s = state;
    last = dynamic_solver.step(s, 12 * hour, true);
    dynamic.push_back(last.seconds_deformation);
  }
  t = summarise_samples(dynamic);
  rows.push_back({label + ": deformation, dynamic step (12 h)", t.median_s, t.min_s, paper.deformation_s, ref,
                  paper.deformation_s / 30.0, std::to_string(last.deformation_cg_iterations) + " CG iterations"});

  // From rest (a first solve): the day-5 moisture from the undeformed shape.
  std::vector<double> from_rest;
  for (int r = 0; r < std::min(options.repetitions, 3); ++r) {
    DesiccationState s = state;
    s.positions = model.body.volume.positions;
    last = solver.step(s, 12 * hour, true);
    from_rest.push_back(last.seconds_deformation);
  }
  t = summarise_samples(from_rest);
  rows.push_back({label + ": deformation, from rest", t.median_s, t.min_s, -1.0, "", -1.0,
                  std::to_string(last.deformation_iterations) + " Newton, " +
                      std::to_string(last.deformation_cg_iterations) +
                      " CG iterations (day-3 solve: " + std::to_string(cold.deformation_iterations) + " Newton)"});
  rows.push_back(
      {label + ": set-up (once per run)", seconds_setup, seconds_setup, -1.0, "", -1.0,
       "pattern, rest-stiffness factorisation, first shape; peak memory so far " + format_mib(peak_rss_bytes())});
}

const RegisterBench desiccation_bench{
    BenchTarget{"desiccation",
                "moisture (dehydration) and volume deformation steps of the arm and head phantoms, beside Table 2 of "
                "Frerichs et al. 2020",
                [](const BenchOptions& options) {
                  std::vector<BenchRow> rows;
                  bench_phantom("arm", options, {0.372, 2.563}, rows);
                  bench_phantom("head", options, {1.463, 8.156}, rows);
                  return rows;
                }}};

}  // namespace
}  // namespace forensim::cli
