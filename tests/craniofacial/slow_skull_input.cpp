#include <gtest/gtest.h>

#include "core/timer.hpp"
#include "craniofacial/head_frame.hpp"
#include "craniofacial/skull_input.hpp"
#include "craniofacial/skull_normals.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "support/test_support.hpp"

using namespace forensim;

// The skull-mesh scan (odedstein/meshes, 100,002 triangles, ~13.9 units tall with the mandible): at 16 mm per
// unit it is about 222 mm tall, an adult's cranium plus mandible.
TEST(SlowSkullInput, SkullMeshScanInMillimetres) {
  FORENSIM_REQUIRE_DATA(path, "skull-mesh/skull.obj");
  SkullInputOptions options;
  options.mesh_units.scale = 16.0;
  Stopwatch watch;
  const Skull skull = load_skull(path, options);
  const double load_s = watch.lap();
  EXPECT_EQ(skull.kind, "mesh");
  EXPECT_EQ(skull.mm_per_unit, 16.0);
  EXPECT_GE(skull.mesh.triangles.size(), 50000u);
  EXPECT_LE(skull.mesh.triangles.size(), 250000u);
  EXPECT_TRUE(check_topology(skull.mesh).is_closed());
  EXPECT_GT(enclosed_volume(skull.mesh), 0.0);
  const BoundingBox box = bounding_box(skull.mesh.positions);
  EXPECT_NEAR(box.size().y(), 13.9 * 16.0, 3.0);
  // The mesh's mirror-symmetry plane (x = 0 in its frame, y up) is found from a rough start.
  Plane start{box.center() + Vec3(4, 0, 0), Eigen::AngleAxisd(0.1, Vec3::UnitY()) * Vec3::UnitX()};
  const SymmetryPlaneFit fit = fit_symmetry_plane(skull.mesh, start);
  const double fit_s = watch.lap();
  EXPECT_GT(std::abs(fit.plane.normal.x()), 0.99);
  EXPECT_LT(fit.rms_mm, 3.0);
  std::printf(
      "skull-mesh: %zu triangles loaded in %.2f s; symmetry plane normal (%.4f %.4f %.4f), rms %.2f mm, "
      "%d iterations, %.2f s\n",
      skull.mesh.triangles.size(), load_s, fit.plane.normal.x(), fit.plane.normal.y(), fit.plane.normal.z(), fit.rms_mm,
      fit.iterations, fit_s);
}

// The headsq CT's bone at its default, the half-maximum height measured across the 1150 surface: above 1150 (3.2 mm
// voxels blur the bone's edge outward), below the bone's own value, and a surface inside the 1150 one.
TEST(SlowSkullInput, HeadsqCtBoneAtItsHalfMaximumHeight) {
  FORENSIM_REQUIRE_DATA(path, "ct-head-headsq/quarter.nhdr");
  SkullInputOptions options;
  options.half_maximum_height = true;
  const Skull measured = load_skull(path, options);
  SkullInputOptions fixed_options;
  fixed_options.bone_iso_value = 1150.0;
  const Skull fixed = load_skull(path, fixed_options);
  ASSERT_TRUE(measured.iso_value && measured.seed_iso_value);
  std::printf("headsq bone threshold %.1f from %zu plateau profiles; enclosed volume %.0f cm^3 (1150: %.0f cm^3)\n",
              *measured.iso_value, measured.threshold_profiles, enclosed_volume(measured.mesh) / 1e3,
              enclosed_volume(fixed.mesh) / 1e3);
  EXPECT_EQ(*measured.seed_iso_value, 1150.0);
  EXPECT_GT(*measured.iso_value, 1300.0);
  EXPECT_LT(*measured.iso_value, 1600.0);
  EXPECT_GT(measured.threshold_profiles, 1000u);
  EXPECT_LT(enclosed_volume(measured.mesh), enclosed_volume(fixed.mesh));
  EXPECT_TRUE(check_topology(measured.mesh).is_closed());
}

// The VTK headsq CT (64 x 64 x 93, 3.2 x 3.2 x 1.5 mm, HU + 1024): the bone surface at SOURCE.md's 1150.
TEST(SlowSkullInput, HeadsqCtBoneSurface) {
  FORENSIM_REQUIRE_DATA(path, "ct-head-headsq/quarter.nhdr");
  SkullInputOptions options;
  options.bone_iso_value = 1150.0;
  Stopwatch watch;
  const Skull skull = load_skull(path, options);
  const double load_s = watch.seconds();
  EXPECT_EQ(skull.kind, "ct");
  EXPECT_GT(skull.mesh.triangles.size(), 10000u);
  EXPECT_LE(skull.mesh.triangles.size(), 250000u);
  EXPECT_GE(skull.components_kept, 1);
  EXPECT_LE(skull.components_kept, 2);
  EXPECT_TRUE(check_topology(skull.mesh).is_closed());
  EXPECT_GT(enclosed_volume(skull.mesh), 0.0);
  const BoundingBox box = bounding_box(skull.mesh.positions);
  // Inside the volume's 205 x 205 x 140 mm; a head's bone spans most of its width.
  EXPECT_LT(box.size().x(), 206.0);
  EXPECT_GT(box.size().x(), 100.0);
  EXPECT_LT(box.size().z(), 141.0);
  // Directions on it are unit and point out of the bone.
  const SkullSurface surface(skull.mesh);
  const Vec3 probe = box.center() + Vec3(0, -box.size().y(), 0);
  const ClosestPoint at = surface.closest_point(probe);
  const Vec3 n = surface.patch_normal(at, 5.0);
  EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  EXPECT_GT(n.dot(probe - at.point), 0.0);
  for (const std::string& note : skull.notes) std::printf("note: %s\n", note.c_str());
  std::printf("headsq bone: %zu triangles in %.2f s, %d of %d components, bbox %.0f x %.0f x %.0f mm\n",
              skull.mesh.triangles.size(), load_s, skull.components_kept, skull.components_found, box.size().x(),
              box.size().y(), box.size().z());
}
