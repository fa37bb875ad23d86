// Benchmarks of the volume module: reading CT, iso-surfacing (the CT phantom, and the real headsq CT when
// the shared data is present).

#include <benchmark/benchmark.h>

#include <filesystem>

#include "core/data_dir.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "volume/iso_surface.hpp"
#include "volume/volume_reader.hpp"

using namespace forensim;

namespace {

std::filesystem::path headsq_path() {
  return shared_data_dir() / "ct-head-headsq" / "quarter.nhdr";
}

const ScalarGrid& phantom_ct() {
  static const ScalarGrid grid = make_ct_head_phantom({2.0, 20.0, 1});
  return grid;
}

void BM_CtPhantomSampling(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(make_ct_head_phantom({4.0, 20.0, 1}));
}
BENCHMARK(BM_CtPhantomSampling)->Unit(benchmark::kMillisecond);

void BM_IsoSurfacePhantom(benchmark::State& state) {
  const ScalarGrid& grid = phantom_ct();
  const double iso = state.range(0) == 0 ? ct_phantom_skin_iso : ct_phantom_bone_iso;
  std::size_t triangles = 0;
  for (auto _ : state) triangles = extract_iso_surface(grid, iso).triangle_count();
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["voxels"] = static_cast<double>(grid.voxel_count());
}
BENCHMARK(BM_IsoSurfacePhantom)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_ReadHeadsqNrrd(benchmark::State& state) {
  if (!std::filesystem::exists(headsq_path())) {
    state.SkipWithError("shared data ct-head-headsq absent");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(read_volume(headsq_path()));
}
BENCHMARK(BM_ReadHeadsqNrrd)->Unit(benchmark::kMillisecond);

void BM_IsoSurfaceHeadsq(benchmark::State& state) {
  if (!std::filesystem::exists(headsq_path())) {
    state.SkipWithError("shared data ct-head-headsq absent");
    return;
  }
  const ScalarGrid grid = read_volume(headsq_path());
  IsoSurfaceOptions options;
  options.keep_largest_components = 1;
  std::size_t triangles = 0;
  for (auto _ : state) triangles = extract_iso_surface(grid, state.range(0), options).triangle_count();
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_IsoSurfaceHeadsq)->Arg(500)->Arg(1150)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
