// Tracking connections at the paper's scale (Frerichs et al. 2020: a 122k-triangle head skin over a coarser
// volume): a 99,848-vertex skin (a cube surface of 129 x 129 quads per side pushed onto a sphere of radius
// 100 mm, 0.3 mm outside the volume) over a 29,791-node ball volume (30^3 cubes, 162,000 tets). Measures
// compute_tracking (boundary extraction, BVH builds, one or two rays per vertex, closest-point fallback)
// and tracking_points (re-evaluating the points for moved nodes, once per skin step). Arg: thread count
// (0 = all hardware threads).
#include <benchmark/benchmark.h>

#include <vector>

#include "body/tracking.hpp"
#include "core/parallel.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

constexpr double radius = 100.0;  // mm, about a head

/// Pushes every point radially from the origin onto |p|_inf / |p|_2 times itself: a cube of half-size r
/// becomes a ball of radius r.
void cube_to_ball(std::vector<Vec3>& points) {
  for (Vec3& p : points) {
    const double norm = p.norm();
    if (norm > 0.0) p *= p.cwiseAbs().maxCoeff() / norm;
  }
}

const TetMesh& volume() {
  static const TetMesh mesh = [] {
    TetMesh m = make_box_tet_mesh(Vec3::Constant(-radius), Vec3::Constant(radius), 30, 30, 30);
    cube_to_ball(m.positions);
    return m;
  }();
  return mesh;
}

const TriMesh& skin() {
  static const TriMesh mesh = [] {
    const double r = radius + 0.3;
    TriMesh m = make_box_mesh(Vec3::Constant(-r), Vec3::Constant(r), 129);
    cube_to_ball(m.positions);
    m.normals.clear();
    return m;
  }();
  return mesh;
}

void BM_ComputeTracking(benchmark::State& state) {
  set_thread_count(static_cast<int>(state.range(0)));
  const TriMesh& s = skin();
  const TetMesh& v = volume();
  TrackingStats stats;
  for (auto _ : state) {
    const TrackingConnections c = compute_tracking(s, v);
    stats = tracking_stats(c);
    benchmark::DoNotOptimize(c.weights.data());
  }
  set_thread_count(0);
  state.counters["skin_vertices"] = static_cast<double>(s.vertex_count());
  state.counters["volume_nodes"] = static_cast<double>(v.vertex_count());
  state.counters["ray_fraction"] = stats.ray_fraction();
  state.counters["max_distance_mm"] = stats.max_distance;
  state.counters["vertices_per_s"] =
      benchmark::Counter(static_cast<double>(s.vertex_count()) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ComputeTracking)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_TrackingPoints(benchmark::State& state) {
  set_thread_count(static_cast<int>(state.range(0)));
  const TrackingConnections c = compute_tracking(skin(), volume());
  std::vector<Vec3> nodes = volume().positions;
  for (Vec3& x : nodes) x *= 0.97;  // a shrunken volume
  for (auto _ : state) {
    const std::vector<Vec3> points = tracking_points(c, nodes);
    benchmark::DoNotOptimize(points.data());
  }
  set_thread_count(0);
  state.counters["points_per_s"] =
      benchmark::Counter(static_cast<double>(c.size()) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TrackingPoints)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
