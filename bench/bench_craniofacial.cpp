// Craniofacial fitting speed: RBF warp setup (eq. 1's LU) for the template's landmark count and for many,
// the warp of every template-head skin vertex, the cached cardinal-function warp, a whole fit of the template
// to a skull, and the interactive case: one landmark moves and the head (skin, muscle grids, muscle shapes)
// follows. The paper reports "about an hour" for a whole reconstruction, mostly interactive work.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include "core/random.hpp"
#include "craniofacial/fit_template.hpp"
#include "craniofacial/rbf_warp.hpp"
#include "craniofacial/template_head.hpp"

using namespace forensim;

namespace {

const TemplateHead& head() {
  static const TemplateHead h = make_template_head();
  return h;
}

/// A target skull: the template's, turned and scaled a little, with its landmarks and depths 10 % larger.
struct Target {
  TriMesh skull;
  LandmarkDepths landmarks;
};

const Target& target() {
  static const Target t = [] {
    Target out;
    const Mat3 a = 1.05 * Eigen::AngleAxisd(0.1, Vec3::UnitZ()).toRotationMatrix();
    out.skull = head().skull;
    for (Vec3& p : out.skull.positions) p = a * p;
    for (const TemplateLandmarkPair& p : head().landmarks) {
      out.landmarks.names.push_back(p.skin_name);
      out.landmarks.skull.push_back(a * p.skull);
      out.landmarks.depth_vectors.push_back(1.1 * (a * (p.skin - p.skull)));
    }
    return out;
  }();
  return t;
}

std::vector<Vec3> random_points(std::size_t n, std::uint64_t seed) {
  RandomStream rng(seed, 0);
  std::vector<Vec3> p(n);
  for (Vec3& x : p) x = Vec3(rng.uniform(-80, 80), rng.uniform(-100, 100), rng.uniform(-100, 140));
  return p;
}

void BM_RbfWarpSetup(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto sources = random_points(n, 1), targets = random_points(n, 2);
  for (auto _ : state) benchmark::DoNotOptimize(RbfWarp(sources, targets).landmark_count());
  state.counters["landmarks"] = static_cast<double>(n);
}

void BM_RbfWarpTemplateSkin(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const RbfWarp warp(random_points(n, 1), random_points(n, 2));
  const auto& points = head().skin.positions;
  for (auto _ : state) benchmark::DoNotOptimize(warp.evaluate_batch(points).data());
  state.counters["vertices"] = static_cast<double>(points.size());
  state.counters["landmarks"] = static_cast<double>(n);
}

void BM_RbfPointWarpTemplateSkin(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto targets = random_points(n, 2);
  const RbfWarp warp(random_points(n, 1), targets);
  const RbfPointWarp cached(warp, head().skin.positions);
  for (auto _ : state) benchmark::DoNotOptimize(cached.warp(targets).data());
  state.counters["vertices"] = static_cast<double>(head().skin.positions.size());
}

void BM_FitTemplate(benchmark::State& state) {
  FitTemplateOptions options;
  options.count_violations = state.range(0) != 0;
  std::size_t pairs = 0;
  for (auto _ : state) {
    const TemplateFitResult r = fit_template(head(), target().skull, target().landmarks, options);
    pairs = r.targets.size();
    benchmark::DoNotOptimize(r.skin.positions.data());
  }
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["skin_vertices"] = static_cast<double>(head().skin.positions.size());
}

void BM_MoveOneLandmark(benchmark::State& state) {
  FitTemplateOptions options;
  options.count_violations = false;
  TemplateFit fit(head(), target().skull, target().landmarks, options);
  const std::string name = state.range(0) == 0 ? "pg'" : "v'";  // a mandible landmark; one of the cranial frame's
  std::size_t i = 0;
  while (target().landmarks.names[i] != name) ++i;
  const Vec3 s = target().landmarks.skull[i], d = target().landmarks.depth_vectors[i];
  double sign = 1.0;
  std::size_t changed = 0;
  for (auto _ : state) {
    changed = fit.move_landmark(name, s + sign * Vec3(0, -1.5, 0.5), d * (1.0 + 0.05 * sign));
    sign = -sign;
  }
  state.counters["changed_targets"] = static_cast<double>(changed);
  state.counters["skin_vertices"] = static_cast<double>(head().skin.positions.size());
}

}  // namespace

BENCHMARK(BM_RbfWarpSetup)->Arg(36)->Arg(150)->Arg(500)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RbfWarpTemplateSkin)->Arg(36)->Arg(150)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RbfPointWarpTemplateSkin)->Arg(150)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FitTemplate)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_MoveOneLandmark)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
