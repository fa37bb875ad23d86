// Time to render the abrasion's key positions (Linnenbank 2015, Table 4.2: 2 / 105 / 126 / 175 / 97 ms and
// 943 ms for all phases at its texture size on a GTX 780) and to sample the timeline (interpolate a map set).
// Two cases:
//  - full: a synthetic canvas whose region is the whole texture (a wound patch of 256 x 256 mm at 8 texels/mm
//    for 2048^2, the thesis's density) holding a concave wound of two ellipses about 60 x 35 mm; the maps
//    are tiled (wound/tiled_map_set.hpp), so each key position computes the tiles of 64^2 texels its maps
//    change (the wound and its 12.5 mm glow) and shares the skin elsewhere, as the thesis's full-screen
//    shaders would if they skipped texels that equal the skin;
//  - patch: a 30 mm stroke on the built-in 188 x 160 mm cylinder, where only the wound's region (the wound
//    and its 12.5 mm glow) is computed and blended.
// A timeline sample is copy-on-write: it blends the tiles where its two key positions differ and shares the
// rest. BM_TimelineSampleFull also expands the sample into a plain full-texture map set (float maps, the
// form written to files), which costs the texture's size.
// Arguments: texture size, worker threads (the goal is for 2 cores: all phases < 94 ms at 2048^2,
// one timeline sample < 5 ms at 2048^2).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>

#include "core/parallel.hpp"
#include "texture/polygon_fill.hpp"
#include "texture/uv_bake.hpp"
#include "wound/abrasion.hpp"
#include "wound/flat_canvas.hpp"
#include "wound/timeline.hpp"
#include "wound/uv_cylinder.hpp"

using namespace forensim;

namespace {

// A canvas covering the whole size x size texture: a concave wound of two overlapping ellipses, distances
// by the exact distance transform (the UV way), 8 texels/mm at 2048.
std::shared_ptr<WoundCanvas> full_canvas(int size) {
  static std::map<int, std::shared_ptr<WoundCanvas>> cache;
  auto& c = cache[size];
  if (c) return c;
  Image upper, lower;
  default_skin_maps(size, size, 5, upper, lower);
  std::vector<std::vector<Vec2>> rings(2);
  for (int k = 0; k < 64; ++k) {
    const double a = 2.0 * M_PI * k / 64.0;
    rings[0].push_back(Vec2(size * (0.42 + 0.12 * std::cos(a)), size * (0.5 + 0.07 * std::sin(a))));
    rings[1].push_back(Vec2(size * (0.58 + 0.06 * std::cos(a)), size * (0.45 + 0.1 * std::sin(a))));
  }
  c = std::make_shared<WoundCanvas>(make_flat_canvas(fill_polygon(size, size, rings), size / 256.0, upper, lower, 5));
  return c;
}

// A 30 mm bent stroke across the UV seam of the built-in cylinder, distances on the surface.
std::shared_ptr<WoundCanvas> patch_canvas(int size) {
  static std::map<int, std::shared_ptr<WoundCanvas>> cache;
  auto& c = cache[size];
  if (c) return c;
  const TriMesh mesh = make_uv_cylinder();
  const UvRaster raster = rasterize_uv(mesh, size, size);
  Image upper, lower;
  default_skin_maps(size, size, 5, upper, lower);
  WoundStroke s;
  s.radius_mm = 5.0;
  for (double a : {-0.25, 0.0, 0.2}) s.points.push_back(Vec3(30.0 * std::cos(a), 30.0 * std::sin(a), 80.0 + 40.0 * a));
  CanvasOptions o;
  o.reach_mm = AbrasionParams{}.reach_mm();
  o.seed = 5;
  c = std::make_shared<WoundCanvas>(make_wound_canvas(mesh, raster, {s}, upper, lower, o));
  return c;
}

std::shared_ptr<WoundCanvas> canvas_for(const benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  return state.range(2) == 0 ? full_canvas(size) : patch_canvas(size);
}

const char* kPhases[] = {"vasoconstriction", "vasodilation", "scab_forming", "scab", "maturation"};

// Arguments: size, threads, case (0 full, 1 patch), phase (0..4, 5 = all).
void BM_AbrasionPhase(benchmark::State& state) {
  const auto canvas = canvas_for(state);
  const int previous = thread_count();
  set_thread_count(static_cast<int>(state.range(1)));
  const int phase = static_cast<int>(state.range(3));
  std::vector<std::shared_ptr<const KeyPosition>> keys;
  for (int p = 0; p < 5; ++p)
    if (phase == 5 || phase == p) keys.push_back(make_abrasion_key(kPhases[p]));
  // Output maps allocated once, as render targets are on a GPU.
  std::vector<TiledMapSet> outputs(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i]->render_into(*canvas, 0.5, outputs[i]);
  for (auto _ : state) {
    for (std::size_t i = 0; i < keys.size(); ++i) {
      keys[i]->render_into(*canvas, 0.5, outputs[i]);
      benchmark::DoNotOptimize(outputs[i].tile(0).color.get());
    }
  }
  set_thread_count(previous);
  std::size_t stored = 0;
  for (const auto& o : outputs) stored += o.stored_texels();
  state.SetLabel(std::string(state.range(2) == 0 ? "full " : "patch ") + (phase == 5 ? "all phases" : kPhases[phase]) +
                 ", region " + std::to_string(canvas->width()) + "x" + std::to_string(canvas->height()) + ", " +
                 std::to_string(stored / 1000) + "k map texels written");
}

// One timeline sample between vasoconstriction and vasodilation (a blend of two map sets), copy-on-write into
// a tiled set. Arguments: size, threads, case.
void BM_TimelineSample(benchmark::State& state) {
  const auto canvas = canvas_for(state);
  Timeline timeline(default_abrasion_timeline());
  timeline.render(canvas);
  TiledMapSet out;
  const int previous = thread_count();
  set_thread_count(static_cast<int>(state.range(1)));
  double t = 400.0;
  timeline.sample(t, out);
  for (auto _ : state) {
    timeline.sample(t, out);
    t = t < 800.0 ? t + 1.0 : 400.0;
    benchmark::DoNotOptimize(out.tile(0).color.get());
  }
  set_thread_count(previous);
  state.SetLabel(std::string(state.range(2) == 0 ? "full" : "patch") + ", region " + std::to_string(canvas->width()) +
                 "x" + std::to_string(canvas->height()) + ", " + std::to_string(out.stored_texels() / 1000) +
                 "k map texels blended");
}

// The same sample written into a full-texture plain map set (float RGBA, reflection, height), as files are
// written. Arguments: size, threads, case.
void BM_TimelineSampleFull(benchmark::State& state) {
  const auto canvas = canvas_for(state);
  Timeline timeline(default_abrasion_timeline());
  timeline.render(canvas);
  MapSet full = skin_map_set(Image(canvas->full_width, canvas->full_height, 4, 0.5f), 0.25f);
  const int previous = thread_count();
  set_thread_count(static_cast<int>(state.range(1)));
  double t = 400.0;
  for (auto _ : state) {
    timeline.sample_full(t, full);
    t = t < 800.0 ? t + 1.0 : 400.0;
    benchmark::DoNotOptimize(full.color.data().data());
  }
  set_thread_count(previous);
  state.SetLabel(std::string(state.range(2) == 0 ? "full" : "patch") + ", region " + std::to_string(canvas->width()) +
                 "x" + std::to_string(canvas->height()));
}

void phase_args(benchmark::internal::Benchmark* b) {
  for (int phase = 0; phase <= 5; ++phase) b->Args({2048, 2, 0, phase});
  b->Args({2048, 1, 0, 5});
  b->Args({4096, 2, 0, 5});
  for (int phase = 0; phase <= 5; ++phase) b->Args({2048, 2, 1, phase});
}

}  // namespace

BENCHMARK(BM_AbrasionPhase)->Apply(phase_args)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TimelineSample)
    ->Args({2048, 2, 0})
    ->Args({2048, 1, 0})
    ->Args({4096, 2, 0})
    ->Args({2048, 2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_TimelineSampleFull)->Args({2048, 2, 0})->Args({4096, 2, 0})->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
