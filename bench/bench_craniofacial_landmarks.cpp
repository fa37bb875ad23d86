// Automatic skull landmarks: registration (similarity + non-rigid) and detection time, the landmark step of the
// CT -> reconstructed head path (goal for the whole path: under 5 s). Cases: the synthetic skull of the tests
// (41k vertices) onto a moved and deformed copy, and the skull-mesh scan (16 mm per unit) as reference onto a moved
// and deformed copy and onto the headsq CT bone surface (skipped when the shared data is absent).
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include "../tests/craniofacial/synthetic_skull.hpp"
#include "core/data_dir.hpp"
#include "craniofacial/landmark_detection.hpp"
#include "craniofacial/skull_input.hpp"
#include "geometry/bounding_box.hpp"

using namespace forensim;

namespace {

TriMesh mapped(TriMesh mesh, const Mat3& r) {
  for (Vec3& p : mesh.positions) p = r * p;
  mesh.normals.clear();
  return mesh;
}

HeadFrame own_frame(const TriMesh& skull) {
  const BoundingBox box = bounding_box(skull.positions);
  HeadFrame f;
  f.midsagittal = fit_symmetry_plane(skull, Plane{box.center(), Vec3::UnitX()}).plane;
  f.origin = f.midsagittal.project(box.center());
  f.frankfort = Plane{f.origin, Vec3::UnitZ()};
  const Vec3 x = (f.midsagittal.normal - f.midsagittal.normal.z() * Vec3::UnitZ()).normalized();
  f.axes.col(0) = x;
  f.axes.col(1) = Vec3::UnitZ().cross(x);
  f.axes.col(2) = Vec3::UnitZ();
  return f;
}

struct Case {
  TriMesh reference;
  HeadFrame frame;
  LandmarkSet landmarks;
  TriMesh target;
};

const Case* skull_mesh_case(bool ct) {
  static const auto make = [](bool to_ct) -> std::optional<Case> {
    const std::filesystem::path mesh_path = shared_data_dir() / "skull-mesh/skull.obj";
    const std::filesystem::path ct_path = shared_data_dir() / "ct-head-headsq/quarter.nhdr";
    if (!std::filesystem::exists(mesh_path) || (to_ct && !std::filesystem::exists(ct_path))) return std::nullopt;
    SkullInputOptions options;
    options.mesh_units.scale = 16.0;
    Mat3 to_lps;
    to_lps << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    Case c;
    c.reference = mapped(load_skull(mesh_path, options).mesh, to_lps);
    c.frame = own_frame(c.reference);
    c.landmarks = locate_landmarks(c.reference, c.frame);
    if (to_ct) {
      SkullInputOptions ct_options;
      ct_options.bone_iso_value = 1150.0;
      c.target = mapped(load_skull(ct_path, ct_options).mesh, Mat3(Eigen::AngleAxisd(M_PI, Vec3::UnitY())));
    } else {
      c.target = test::moved(c.reference, test::known_similarity(), true);
    }
    return c;
  };
  static const std::optional<Case> copy = make(false);
  static const std::optional<Case> onto_ct = make(true);
  const std::optional<Case>& c = ct ? onto_ct : copy;
  return c ? &*c : nullptr;
}

void BM_DetectSyntheticSkull(benchmark::State& state) {
  const TriMesh reference = test::skull_mesh(6);
  const LandmarkSet landmarks = refine_landmarks(reference, test::identity_frame(), test::rough_skull_landmarks());
  const TriMesh target = test::moved(reference, test::known_similarity(), true);
  for (auto _ : state) benchmark::DoNotOptimize(detect_landmarks(reference, landmarks, target));
  state.counters["vertices"] = static_cast<double>(target.positions.size());
}
BENCHMARK(BM_DetectSyntheticSkull)->Unit(benchmark::kMillisecond)->Iterations(2);

void BM_DetectSkullMesh(benchmark::State& state) {
  const bool ct = state.range(0) != 0;
  const Case* c = skull_mesh_case(ct);
  if (!c) {
    state.SkipWithError("shared data skull-mesh / ct-head-headsq not found (set FORENSIM_DATA_DIR)");
    return;
  }
  LandmarkDetectionOptions options;
  if (ct) {
    options.registration.similarity.trim_fraction = 0.4;
    options.registration.non_rigid.trim_fraction = 0.4;
  }
  for (auto _ : state)
    benchmark::DoNotOptimize(detect_landmarks(c->reference, c->landmarks, c->frame, c->target, options));
  state.counters["target_triangles"] = static_cast<double>(c->target.triangles.size());
}
BENCHMARK(BM_DetectSkullMesh)->Arg(0)->Arg(1)->ArgNames({"onto_ct"})->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_RegisterSkullMesh(benchmark::State& state) {
  const Case* c = skull_mesh_case(false);
  if (!c) {
    state.SkipWithError("shared data skull-mesh not found (set FORENSIM_DATA_DIR)");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(register_skull(c->reference, c->target));
}
BENCHMARK(BM_RegisterSkullMesh)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
