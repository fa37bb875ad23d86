#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"
#include "volume/iso_surface.hpp"
#include "volume/metaimage_reader.hpp"
#include "volume/nrrd_reader.hpp"
#include "volume/volume_reader.hpp"

using namespace forensim;

namespace {

double milliseconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// End to end on the VTK headsq CT: the skin and the skull as a user would extract them (largest component, Taubin
// smoothing, optionally at half resolution), and the CT through every writer and back. Prints the figures quoted in
// the volume module's commit messages.
TEST(HeadCt, SkinAndSkullEndToEnd) {
  FORENSIM_REQUIRE_DATA(path, "ct-head-headsq/quarter.nhdr");
  auto t0 = std::chrono::steady_clock::now();
  const ScalarGrid ct = read_volume(path);
  std::printf("read %d x %d x %d in %.1f ms\n", ct.nx, ct.ny, ct.nz, milliseconds_since(t0));
  for (const double iso : {500.0, 1150.0}) {
    for (const double factor : {1.0, 2.0}) {
      IsoSurfaceOptions options;
      options.keep_largest_components = 1;
      options.smoothing_iterations = 10;
      options.resample_factor = factor;
      t0 = std::chrono::steady_clock::now();
      const TriMesh mesh = extract_iso_surface(ct, iso, options);
      const double ms = milliseconds_since(t0);
      const TopologyReport r = check_topology(mesh);
      const Vec3 size = bounding_box(mesh.positions).size();
      std::printf(
          "iso %.0f, resample %.0f, largest component, 10 Taubin steps: %zu triangles, bbox %.1f x %.1f x "
          "%.1f mm, %.0f ml, %s, %.1f ms\n",
          iso, factor, mesh.triangle_count(), size.x(), size.y(), size.z(), enclosed_volume(mesh) / 1000.0,
          r.summary().c_str(), ms);
      EXPECT_TRUE(r.is_closed() && r.is_manifold() && r.is_oriented()) << r.summary();
      EXPECT_EQ(r.component_count, 1u);
      EXPECT_GT(size.x(), 120.0);
      EXPECT_LT(size.x(), 210.0);
    }
  }
  const auto dir = test::scratch_dir("ct");
  write_nrrd(dir / "ct.nrrd", ct, true);
  write_nrrd(dir / "ct.nhdr", ct, false);
  write_metaimage(dir / "ct.mhd", ct, true);
  for (const char* name : {"ct.nrrd", "ct.nhdr", "ct.mhd"}) {
    const ScalarGrid back = read_volume(dir / name);
    EXPECT_EQ(back.values, ct.values) << name;
    EXPECT_EQ(back.spacing, ct.spacing) << name;
  }
}
