// Facial expressions by muscle contraction on the built-in template head (Kähler, Haber and Seidel 2003,
// section 5): building the skin-muscle-skull spring model and its solver (Hessian pattern, CHOLMOD analysis),
// and the time per expression (projected Newton to static equilibrium) for each preset, on one thread and on
// all (Arg: threads, 0 = all).
#include <benchmark/benchmark.h>

#include "core/parallel.hpp"
#include "craniofacial/face_expression.hpp"
#include "craniofacial/template_head.hpp"

using namespace forensim;

namespace {

const TemplateHead& head() {
  static const TemplateHead h = make_template_head();
  return h;
}

const std::vector<MuscleShape>& muscles() {
  static const std::vector<MuscleShape> m = shape_muscles(head().muscles, head().skin);
  return m;
}

void BM_BuildExpressionModel(benchmark::State& state) {
  set_thread_count(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    FaceExpressions e(head().skin, head().skull, muscles());
    benchmark::DoNotOptimize(e.model().node_rest_positions.data());
  }
  state.counters["skin_vertices"] = static_cast<double>(head().skin.positions.size());
  set_thread_count(0);
}

void BM_Expression(benchmark::State& state, const std::string& preset) {
  set_thread_count(static_cast<int>(state.range(0)));
  static const FaceExpressions expressions(head().skin, head().skull, muscles());
  int iterations = 0;
  for (auto _ : state) {
    const FaceExpression e = expressions.preset(preset);
    iterations = e.newton_iterations;
    benchmark::DoNotOptimize(e.skin_positions.data());
  }
  state.counters["newton_iterations"] = iterations;
  state.counters["skin_vertices"] = static_cast<double>(head().skin.positions.size());
  set_thread_count(0);
}

}  // namespace

BENCHMARK(BM_BuildExpressionModel)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_Expression, smile, std::string("smile"))
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_Expression, frown, std::string("frown"))->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_Expression, surprise, std::string("surprise"))
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);

BENCHMARK_MAIN();
