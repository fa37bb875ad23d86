// Throughput of the wound texture techniques at 2048 x 2048 texels (a wound patch at 20 texels/mm covers
// about 10 x 10 cm): value noise as the thesis's scab-forming layer (Algorithm 3.2, 5 octaves), the exact
// distance transform of a wound-shaped mask (Felzenszwalb-Huttenlocher), the gradient edge drawn through it,
// shape erosion (Algorithm 3.1) and the tileable noises. Wall-clock times (parallel at the current thread
// count); inputs are seeded, so runs are comparable.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/convex_hull.hpp"
#include "texture/distance_transform.hpp"
#include "texture/gradient_edge.hpp"
#include "texture/polygon_fill.hpp"
#include "texture/shape_erosion.hpp"
#include "texture/tile_noise.hpp"
#include "texture/value_noise.hpp"

using namespace forensim;

namespace {

constexpr int size = 2048;

// Convex hull of random points in an ellipse, in texels: the shape a user draws for an abrasion.
const std::vector<Vec2>& wound_hull() {
  static const std::vector<Vec2> hull = [] {
    RandomStream rng(3, 0);
    std::vector<Vec2> points;
    for (int i = 0; i < 400; ++i) {
      const double a = rng.uniform(0.0, 6.283185307179586), r = std::sqrt(rng.uniform());
      points.emplace_back(size * (0.5 + 0.3 * r * std::cos(a)), size * (0.5 + 0.2 * r * std::sin(a)));
    }
    return convex_hull(points);
  }();
  return hull;
}

const Image& wound_mask() {
  static const Image mask = fill_polygon(size, size, {wound_hull()});
  return mask;
}

// Arguments: octaves, worker threads.
void BM_ValueNoise(benchmark::State& state) {
  ValueNoiseParams params;
  params.octaves = static_cast<int>(state.range(0));
  params.persistence = 0.85;
  params.bias = 0.54;
  params.gain = 0.21;
  const Image base = value_noise_base(size, size, 1);
  const int previous = thread_count();
  set_thread_count(static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(value_noise(base, params).data().data());
  set_thread_count(previous);
  state.SetItemsProcessed(state.iterations() * size * size);
}
BENCHMARK(BM_ValueNoise)->Args({5, 1})->Args({5, 2})->Args({10, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

// Argument: worker threads.
void BM_SquaredDistanceTransform(benchmark::State& state) {
  const std::vector<std::uint8_t> mask = binary_mask(wound_mask());
  const int previous = thread_count();
  set_thread_count(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(squared_distance_transform(mask, size, size).data());
  set_thread_count(previous);
  state.SetItemsProcessed(state.iterations() * size * size);
}
BENCHMARK(BM_SquaredDistanceTransform)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SignedDistance(benchmark::State& state) {
  const Image& mask = wound_mask();
  for (auto _ : state) benchmark::DoNotOptimize(signed_distance(mask).data().data());
  state.SetItemsProcessed(state.iterations() * size * size);
}
BENCHMARK(BM_SignedDistance)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GradientEdgeMask(benchmark::State& state) {
  const Image& mask = wound_mask();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        draw_gradient_edge(mask, 100.0, GradientSide::outside, Vec4f(0.79f, 0, 0, 1), Vec4f(0.9f, 0.7f, 0.6f, 1))
            .data()
            .data());
  state.SetItemsProcessed(state.iterations() * size * size);
}
BENCHMARK(BM_GradientEdgeMask)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GradientEdgeHull(benchmark::State& state) {
  const Image& mask = wound_mask();
  for (auto _ : state)
    benchmark::DoNotOptimize(draw_gradient_edge_hull(wound_hull(), mask, 100.0, GradientSide::outside,
                                                     Vec4f(0.79f, 0, 0, 1), Vec4f(0.9f, 0.7f, 0.6f, 1))
                                 .data()
                                 .data());
  state.SetItemsProcessed(state.iterations() * size * size);
  state.counters["hull_vertices"] = static_cast<double>(wound_hull().size());
}
BENCHMARK(BM_GradientEdgeHull)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ShapeErosion(benchmark::State& state) {
  const Image& mask = wound_mask();
  const std::vector<int> widths = random_erosion_widths(size, size, 3, 10, 2);
  for (auto _ : state) benchmark::DoNotOptimize(erode_shape(mask, widths).data().data());
  state.SetItemsProcessed(state.iterations() * size * size);
}
BENCHMARK(BM_ShapeErosion)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_TilePerlinImage(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(tile_perlin_image(size, size, 8, 8, 5, 0.5, 1).data().data());
  state.SetItemsProcessed(state.iterations() * size * size);
}
BENCHMARK(BM_TilePerlinImage)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_TileWorleyImage(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(tile_worley_image(size, size, 32, 32, WorleyFeature::f1, 1).data().data());
  state.SetItemsProcessed(state.iterations() * size * size);
}
BENCHMARK(BM_TileWorleyImage)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
