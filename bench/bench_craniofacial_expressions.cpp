// Facial expressions by muscle contraction on the built-in template head (Kähler, Haber and Seidel 2003,
// section 5): building the skin-muscle-skull spring model and its solver (the quasi-Newton method factors the
// projective-dynamics matrix once), and the time per expression for each preset, on one thread and on all
// (Arg: threads, 0 = all). BM_ExpressionNewton solves the same presets with the projected-Newton reference
// (one Cholesky refactorisation per step); its counter max_difference_mm is the largest distance between a
// skin vertex of the two equilibria.
#include <benchmark/benchmark.h>

#include <algorithm>

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

const FaceExpressions& quasi_newton() {
  static const FaceExpressions e(head().skin, head().skull, muscles());
  return e;
}

void BM_BuildExpressionModel(benchmark::State& state) {
  muscles();  // the template head is built once, outside the timing
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
  const FaceExpressions& expressions = quasi_newton();
  int iterations = 0;
  for (auto _ : state) {
    const FaceExpression e = expressions.preset(preset);
    iterations = e.newton_iterations;
    benchmark::DoNotOptimize(e.skin_positions.data());
  }
  state.counters["iterations"] = iterations;
  state.counters["skin_vertices"] = static_cast<double>(head().skin.positions.size());
  set_thread_count(0);
}

void BM_ExpressionNewton(benchmark::State& state, const std::string& preset) {
  set_thread_count(static_cast<int>(state.range(0)));
  MuscleContractionOptions options;
  options.method = ContractionMethod::newton;
  static const FaceExpressions newton(head().skin, head().skull, muscles(), {}, options);
  FaceExpression e;
  for (auto _ : state) {
    e = newton.preset(preset);
    benchmark::DoNotOptimize(e.skin_positions.data());
  }
  const FaceExpression q = quasi_newton().preset(preset);
  double difference = 0.0;
  for (std::size_t i = 0; i < e.skin_positions.size(); ++i) {
    difference = std::max(difference, (e.skin_positions[i] - q.skin_positions[i]).norm());
  }
  state.counters["iterations"] = e.newton_iterations;
  state.counters["max_difference_mm"] = difference;
  set_thread_count(0);
}

}  // namespace

BENCHMARK(BM_BuildExpressionModel)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_Expression, smile, std::string("smile"))->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Expression, frown, std::string("frown"))->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Expression, worried, std::string("worried"))->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Expression, surprise, std::string("surprise"))->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ExpressionNewton, smile, std::string("smile"))
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_ExpressionNewton, surprise, std::string("surprise"))
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

BENCHMARK_MAIN();
