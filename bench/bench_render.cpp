// Renderer and image benchmarks. The target from the brief: a 1024 x 1024 picture of a ~100k-triangle
// mesh with soft shadows in a few seconds on 2 cores. Run:
//   build/<dir>/bin/forensim_bench_render --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "image/png_io.hpp"
#include "render/renderer.hpp"

using namespace forensim;

namespace {

// A bumpy, head-sized blob of 81,920 triangles (icosphere level 6) over an inner "skull" of 20,480:
// ~102k triangles in all.
Scene make_scene() {
  TriMesh skin = make_icosphere(Vec3::Zero(), 90.0, 6);
  for (Vec3& p : skin.positions) {
    const Vec3 n = p.normalized();
    p *= 1.0 + 0.04 * std::sin(7 * n[0]) * std::sin(5 * n[1]) * std::cos(6 * n[2]) + 0.2 * n[2] * n[2];
  }
  compute_normals(skin);
  Scene scene;
  scene.add(make_icosphere(Vec3::Zero(), 70.0, 5), SurfaceMaterial::bone(), "skull");
  scene.add(std::make_shared<const TriMesh>(std::move(skin)), SurfaceMaterial::skin(), "skin");
  scene.frame(ViewName::three_quarter, 1.0);
  return scene;
}

void BM_RenderScene(benchmark::State& state) {
  set_thread_count(static_cast<int>(state.range(1)));
  const Scene scene = make_scene();
  const Renderer renderer(scene);
  RenderSettings settings;
  settings.width = 1024;
  settings.height = 1024;
  settings.samples_per_pixel = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(settings));
  state.counters["triangles"] = 81920 + 20480;
  state.counters["Mpixel_samples/s"] = benchmark::Counter(1024.0 * 1024.0 * settings.samples_per_pixel / 1e6,
                                                          benchmark::Counter::kIsIterationInvariantRate);
  set_thread_count(0);
}
BENCHMARK(BM_RenderScene)
    ->Args({4, 2})
    ->Args({8, 2})
    ->Args({16, 2})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_BuildRenderer(benchmark::State& state) {
  const Scene scene = make_scene();
  for (auto _ : state) {
    const Renderer renderer(scene);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_BuildRenderer)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EncodePng(benchmark::State& state) {
  Image image(1024, 1024, 4);
  for (std::size_t i = 0; i < image.data().size(); ++i)
    image.data()[i] = static_cast<float>((i * 7919) % 1000) / 1000.0f;
  for (auto _ : state) benchmark::DoNotOptimize(encode_png(image));
}
BENCHMARK(BM_EncodePng)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
