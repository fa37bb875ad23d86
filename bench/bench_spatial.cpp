// Throughput of forensim's spatial queries on a 100k-triangle sphere (icosphere, 6 subdivisions: 81,920
// triangles, and 7: 327,680; the 100k case lies between): ray casts per second (single and batch), closest points per
// second and fast winding-number queries per second. Batch timings are wall-clock (parallel); single ones are per
// thread. Queries are random but seeded, so runs are comparable.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "core/random.hpp"
#include "geometry/primitives.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/ray_caster.hpp"
#include "spatial/winding_number.hpp"

using namespace forensim;

namespace {

constexpr double radius = 100.0;  // mm, about a head

const TriMesh& sphere(int subdivisions) {
  static const TriMesh s6 = make_icosphere(Vec3::Zero(), radius, 6);
  static const TriMesh s7 = make_icosphere(Vec3::Zero(), radius, 7);
  return subdivisions == 6 ? s6 : s7;
}

std::vector<Vec3> random_points(std::size_t count, double spread, std::uint64_t seed) {
  RandomStream rng(seed, 0);
  std::vector<Vec3> points(count);
  for (Vec3& p : points)
    p = Vec3(rng.uniform(-spread, spread), rng.uniform(-spread, spread), rng.uniform(-spread, spread));
  return points;
}

std::vector<Vec3> random_directions(std::size_t count, std::uint64_t seed) {
  RandomStream rng(seed, 1);
  std::vector<Vec3> directions(count);
  for (Vec3& d : directions) {
    const double z = rng.uniform(-1.0, 1.0);
    const double phi = rng.uniform(0.0, 6.283185307179586);
    const double s = std::sqrt(1.0 - z * z);
    d = Vec3(s * std::cos(phi), s * std::sin(phi), z);
  }
  return directions;
}

/// Points within 5 % of the radius from the surface: the skin-attachment case (points in the middle of a
/// sphere are the worst case of any closest-point search, every part of the surface being nearly as close).
std::vector<Vec3> near_surface_points(std::size_t count, std::uint64_t seed) {
  std::vector<Vec3> points = random_directions(count, seed);
  RandomStream rng(seed, 2);
  for (Vec3& p : points) p *= radius * rng.uniform(0.95, 1.05);
  return points;
}

constexpr std::size_t query_count = 1 << 16;

void BM_RayCasterBuild(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    RayCaster caster(mesh);
    benchmark::DoNotOptimize(caster.triangle_count());
  }
  state.counters["triangles"] = static_cast<double>(mesh.triangle_count());
}

void BM_RayCastSingle(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  const RayCaster caster(mesh);
  const auto origins = random_points(query_count, 1.5 * radius, 1);
  const auto directions = random_directions(query_count, 2);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(caster.intersect(origins[i], directions[i]));
    i = (i + 1) % query_count;
  }
  state.counters["rays/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_RayCastBatch(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  const RayCaster caster(mesh);
  const auto origins = random_points(query_count, 1.5 * radius, 1);
  const auto directions = random_directions(query_count, 2);
  for (auto _ : state) benchmark::DoNotOptimize(caster.intersect_batch(origins, directions));
  state.counters["rays/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * query_count), benchmark::Counter::kIsRate);
}

void BM_ClosestPointSingle(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  const ClosestPointQuery query(mesh);
  const auto points = random_points(query_count, 1.5 * radius, 3);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(query.query(points[i]));
    i = (i + 1) % query_count;
  }
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_ClosestPointNearSurface(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  const ClosestPointQuery query(mesh);
  const auto points = near_surface_points(query_count, 5);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(query.query(points[i]));
    i = (i + 1) % query_count;
  }
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_ClosestPointBatch(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  const ClosestPointQuery query(mesh);
  const auto points = random_points(query_count, 1.5 * radius, 3);
  for (auto _ : state) benchmark::DoNotOptimize(query.query_batch(points));
  state.counters["points/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * query_count), benchmark::Counter::kIsRate);
}

void BM_WindingNumberBuild(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    WindingNumber w(mesh);
    benchmark::DoNotOptimize(w.node_count());
  }
}

void BM_WindingNumberSingle(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  const WindingNumber winding(mesh);
  const auto points = random_points(query_count, 1.5 * radius, 4);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(winding.evaluate(points[i]));
    i = (i + 1) % query_count;
  }
  state.counters["queries/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_WindingNumberBatch(benchmark::State& state) {
  const TriMesh& mesh = sphere(static_cast<int>(state.range(0)));
  const WindingNumber winding(mesh);
  const auto points = random_points(query_count, 1.5 * radius, 4);
  for (auto _ : state) benchmark::DoNotOptimize(winding.evaluate_batch(points));
  state.counters["queries/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * query_count), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_RayCasterBuild)->Arg(6)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RayCastSingle)->Arg(6)->Arg(7);
BENCHMARK(BM_RayCastBatch)->Arg(6)->Arg(7)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ClosestPointSingle)->Arg(6)->Arg(7);
BENCHMARK(BM_ClosestPointNearSurface)->Arg(6)->Arg(7);
BENCHMARK(BM_ClosestPointBatch)->Arg(6)->Arg(7)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WindingNumberBuild)->Arg(6)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WindingNumberSingle)->Arg(6)->Arg(7);
BENCHMARK(BM_WindingNumberBatch)->Arg(6)->Arg(7)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
