// Per-frame cost of the mummification skin shading (eqs. 36 to 39 per skin vertex) on the `paper` skins of
// the built-in phantoms (arm about 19k triangles, head about 122k, as Table 1 of Frerichs, Vidler and Gatzidis
// 2020; the paper's per-frame times of Table 2 include its GPU skin rendering, so they are not comparable
// beside these). The skins are built as make_phantom_model() builds them (skin iso-surface remeshed to the
// triangle target), without the tet volume. BM_ShadeFrame: one frame with a varying moisture field.
// BM_BakeFrame: the forearm-uv phantom's shaded colours baked into a UV map per frame. BM_GenerateLut: the
// look-up texture, made once per run. Timings are wall-clock (UseRealTime).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <string>

#include "body/phantom_model.hpp"
#include "geometry/mesh_measures.hpp"
#include "mesh_processing/remesh_isotropic.hpp"
#include "phantoms/forearm_uv.hpp"
#include "phantoms/phantom.hpp"
#include "phantoms/phantom_surface.hpp"
#include "skin/skin_map_baker.hpp"
#include "skin/skin_shader.hpp"

using namespace forensim;

namespace {

struct SkinCase {
  TriMesh skin;
  LivorState livor;
  SkinLayers layers;
  std::vector<double> moisture;
};

SkinCase make_case(TriMesh skin) {
  SkinCase c;
  c.skin = std::move(skin);
  c.livor = settle_livor(c.skin, contact_near_plane(c.skin, Vec3(0, 0, -1), 3.0));
  c.layers = uniform_skin_layers(c.skin.vertex_count());
  c.moisture.resize(c.skin.vertex_count());
  for (std::size_t i = 0; i < c.moisture.size(); ++i)
    c.moisture[i] = 0.5 + 0.5 * std::sin(0.05 * c.skin.positions[i][0] + 0.03 * c.skin.positions[i][1]);
  return c;
}

const SkinCase& paper_skin(const std::string& phantom_name) {
  static std::map<std::string, SkinCase> cases;
  auto it = cases.find(phantom_name);
  if (it != cases.end()) return it->second;
  const PhantomModelSize size = phantom_model_size(phantom_name, "paper");
  const auto phantom = make_phantom(phantom_name);
  const TriMesh source = phantom_surface(*phantom, PhantomSurface::skin, size.skin_voxel_mm);
  const double target = static_cast<double>(size.skin_triangles);
  const double edge = std::sqrt(4.0 * surface_area(source) / (std::sqrt(3.0) * target));
  TriMesh skin = remesh_isotropic(source, edge, 3);
  const double got = static_cast<double>(skin.triangle_count());
  if (std::abs(got - target) > 0.05 * target) skin = remesh_isotropic(source, edge * std::sqrt(got / target), 3);
  return cases.emplace(phantom_name, make_case(std::move(skin))).first->second;
}

const SkinShader& shader() {
  static const SkinShader s;
  return s;
}

void BM_ShadeFrame(benchmark::State& bench, const std::string& phantom_name) {
  const SkinCase& c = paper_skin(phantom_name);
  std::vector<Vec4f> colours;
  double hours = 0.0;
  for (auto _ : bench) {
    shader().shade(c.layers, c.livor, c.moisture, hours, colours);
    hours += 24.0;
    benchmark::DoNotOptimize(colours.data());
  }
  bench.counters["vertices"] = static_cast<double>(c.skin.vertex_count());
  bench.counters["triangles"] = static_cast<double>(c.skin.triangle_count());
}
BENCHMARK_CAPTURE(BM_ShadeFrame, arm_paper, std::string("arm"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ShadeFrame, head_paper, std::string("head"))->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BakeFrame(benchmark::State& bench) {
  static const SkinCase c = make_case(make_forearm_uv().mesh);
  const int resolution = static_cast<int>(bench.range(0));
  const SkinMapBaker baker(c.skin, resolution);
  std::vector<Vec4f> colours;
  for (auto _ : bench) {
    shader().shade(c.layers, c.livor, c.moisture, 48.0, colours);
    const Image map = baker.bake_colours(colours);
    benchmark::DoNotOptimize(map.data().data());
  }
  bench.counters["vertices"] = static_cast<double>(c.skin.vertex_count());
  bench.counters["texels"] = static_cast<double>(baker.covered_texels());
}
BENCHMARK(BM_BakeFrame)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GenerateLut(benchmark::State& bench) {
  for (auto _ : bench) {
    const DermisLut lut;
    benchmark::DoNotOptimize(lut.texel(0, 0));
  }
}
BENCHMARK(BM_GenerateLut)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
