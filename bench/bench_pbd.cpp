// Cost of one skin step (position-based dynamics with tracking, slippage and collisions, src/pbd) on the `paper`
// body models, beside Table 2 of Frerichs, Vidler and Gatzidis 2020 (per skin deformation step on an i7 at
// 3.4 GHz: arm 0.173 s with 19k skin triangles, head 1.221 s with 122k). The volume is shrunk 3 % about its
// centre and the skin half dried, so pulls and collisions are active; the steps run on from one another.
// The models are built once (arm about 25 s, head longer). Timings are wall-clock (UseRealTime), on one thread
// and on all.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "body/phantom_model.hpp"
#include "core/parallel.hpp"
#include "pbd/skin_simulation.hpp"

using namespace forensim;

namespace {

struct Setup {
  BodyModel body;
  SkinModel skin;
  std::vector<Vec3> nodes;
};

const Setup& setup(const std::string& phantom) {
  static std::map<std::string, std::unique_ptr<Setup>> cache;
  auto& s = cache[phantom];
  if (!s) {
    s = std::make_unique<Setup>();
    s->body = make_phantom_model(phantom_model_size(phantom, "paper"));
    s->skin = make_skin_model(s->body);
    Vec3 centre = Vec3::Zero();
    for (const Vec3& p : s->body.volume.positions) centre += p;
    centre /= static_cast<double>(s->body.volume.vertex_count());
    s->nodes = s->body.volume.positions;
    for (Vec3& p : s->nodes) p = centre + 0.97 * (p - centre);
  }
  return *s;
}

void skin_step(benchmark::State& bench, const std::string& phantom, double paper_s) {
  const Setup& s = setup(phantom);
  set_thread_count(static_cast<int>(bench.range(0)));
  SkinSimulation sim(s.skin);
  SkinState state = initial_skin_state(s.skin);
  const std::vector<double> moisture(s.skin.vertex_count(), 0.5);
  SkinStepReport report;
  for (auto _ : bench) {
    report = sim.step(state, s.nodes, moisture, 1.0 / 30.0);
    benchmark::DoNotOptimize(state.positions.data());
  }
  bench.counters["skin_vertices"] = static_cast<double>(s.skin.vertex_count());
  bench.counters["skin_triangles"] = static_cast<double>(s.skin.triangles.size());
  bench.counters["stretch_groups"] = static_cast<double>(s.skin.stretch_groups.size());
  bench.counters["bending_groups"] = static_cast<double>(s.skin.bending_groups.size());
  bench.counters["collisions"] = static_cast<double>(report.collisions);
  bench.counters["paper_s"] = paper_s;
  set_thread_count(0);
}

void BM_SkinStepArm(benchmark::State& bench) {
  skin_step(bench, "arm", 0.173);
}
void BM_SkinStepHead(benchmark::State& bench) {
  skin_step(bench, "head", 1.221);
}

}  // namespace

// Argument: worker threads (0 = all).
BENCHMARK(BM_SkinStepArm)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SkinStepHead)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
