#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/error.hpp"
#include "craniofacial/skull_input.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "phantoms/ct_head_phantom.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

/// A CT-like volume stored as HU + 1024 (air 0): a large bone ball (the "cranium"), a smaller one (the
/// "mandible") and a bone speck. Values fall off linearly with distance across each surface (100 per mm, crossing
/// the bone iso-value 1150 exactly at the ball's radius), so the extracted surface lies on the spheres.
ScalarGrid synthetic_ct() {
  ScalarGrid grid = ScalarGrid::filled(48, 48, 40, 0.0f);
  grid.spacing = Vec3(2.0, 2.0, 2.5);
  grid.origin = Vec3(-48, -48, -50);
  struct Ball {
    Vec3 center;
    double radius;
  };
  const Ball balls[] = {{Vec3(0, 0, 10), 30.0}, {Vec3(0, -20, -36), 12.0}, {Vec3(30, 30, -35), 2.6}};
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        const Vec3 p = grid.index_to_world(Vec3(i, j, k));
        double v = 0.0;
        for (const Ball& b : balls) v = std::max(v, 1150.0 + 100.0 * (b.radius - (p - b.center).norm()));
        grid.at(i, j, k) = static_cast<float>(std::clamp(v, 0.0, 2024.0));
      }
    }
  }
  return grid;
}

}  // namespace

TEST(SkullInput, CtBoneSurfaceKeepsTheLargestComponentsOutwardAndInMillimetres) {
  const ScalarGrid ct = synthetic_ct();
  SkullInputOptions options;
  options.min_triangles = 0;
  const Skull skull = skull_from_volume(ct, "synthetic CT", options);
  EXPECT_EQ(skull.kind, "ct");
  ASSERT_TRUE(skull.iso_value);
  EXPECT_EQ(*skull.iso_value, 1150.0);  // default 126 HU on HU + 1024 storage
  EXPECT_EQ(skull.components_found, 3);
  EXPECT_EQ(skull.components_kept, 2);  // the speck is dropped
  const TopologyReport topology = check_topology(skull.mesh);
  EXPECT_TRUE(topology.is_closed());
  EXPECT_EQ(topology.component_count, 2u);
  EXPECT_GT(enclosed_volume(skull.mesh), 0.0);
  // Volume of the two balls (r 30 and r 12 mm), within the discretisation.
  const double expected = 4.0 / 3.0 * M_PI * (30.0 * 30.0 * 30.0 + 12.0 * 12.0 * 12.0);
  EXPECT_NEAR(enclosed_volume(skull.mesh), expected, 0.03 * expected);
  const BoundingBox box = bounding_box(skull.mesh.positions);
  EXPECT_NEAR(box.max.z(), 40.0, 2.5);
  EXPECT_NEAR(box.min.z(), -48.0, 2.5);
  EXPECT_EQ(skull.mesh.normals.size(), skull.mesh.positions.size());
}

TEST(SkullInput, DecimatesAboveTheTriangleBound) {
  SkullInputOptions options;
  options.max_triangles = 1500;
  options.min_triangles = 1000;
  const Skull skull = skull_from_volume(synthetic_ct(), "synthetic CT", options);
  EXPECT_LE(skull.mesh.triangles.size(), 1500u);
  EXPECT_GT(skull.input_triangles, 1500u);
  EXPECT_TRUE(check_topology(skull.mesh).is_closed());
  bool noted = false;
  for (const std::string& n : skull.notes) noted = noted || n.find("decimated") != std::string::npos;
  EXPECT_TRUE(noted);
  // An explicit iso-value above every voxel finds nothing.
  options.bone_iso_value = 5000.0;
  EXPECT_THROW(skull_from_volume(synthetic_ct(), "synthetic CT", options), InputError);
}

TEST(SkullInput, InwardMeshesAreTurnedOutward) {
  TriMesh mesh = make_icosphere(Vec3(0, 0, 0), 90.0, 3);
  for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
  ASSERT_LT(enclosed_volume(mesh), 0.0);
  const Skull skull = skull_from_mesh(mesh, "inward sphere");
  EXPECT_GT(enclosed_volume(skull.mesh), 0.0);
  EXPECT_EQ(skull.components_kept, 1);
  EXPECT_THROW(skull_from_mesh(TriMesh{}, "empty"), InputError);
}

TEST(SkullInput, MeshFilesInOtherUnitsComeInMillimetres) {
  const auto dir = forensim::test::scratch_dir("skull_input_obj");
  const auto path = dir / "tetra.obj";
  {
    std::ofstream out(path);
    out << "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 0 10\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  }
  SkullInputOptions options;
  options.mesh_units.unit = "cm";
  const Skull skull = load_skull(path, options);
  EXPECT_EQ(skull.kind, "mesh");
  EXPECT_EQ(skull.mm_per_unit, 10.0);
  const BoundingBox box = bounding_box(skull.mesh.positions);
  EXPECT_NEAR(box.max.x(), 100.0, 1e-9);
  EXPECT_GT(enclosed_volume(skull.mesh), 0.0);
  EXPECT_FALSE(is_volume_path(path));
  EXPECT_TRUE(is_volume_path(dir));
  EXPECT_TRUE(is_volume_path(dir / "head.nhdr"));
  std::filesystem::remove_all(dir);
}

namespace {

/// A skull-like CT stored as HU + 1024: a bone shell 10 mm thick (1800) in soft tissue (1000) in air, on
/// 2 x 2 x 2.5 mm voxels, each edge blurred by a Gaussian of 1 mm (erfc steps).
ScalarGrid blurred_shell_ct(double outer, double inner) {
  ScalarGrid grid = ScalarGrid::filled(64, 64, 52, 0.0f);
  grid.spacing = Vec3(2.0, 2.0, 2.5);
  grid.origin = Vec3(-63, -63, -63.75);
  const auto step = [](double inside_by) { return 0.5 * std::erfc(-inside_by / std::sqrt(2.0)); };
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        const double r = grid.index_to_world(Vec3(i, j, k)).norm();
        const double v = 1000.0 * step(outer + 12.0 - r) + 800.0 * (step(outer - r) - step(inner - r));
        grid.at(i, j, k) = static_cast<float>(v);
      }
    }
  }
  return grid;
}

double mean_radius(const TriMesh& mesh, bool outer_half) {
  double sum = 0.0, count = 0.0, split = 0.0;
  for (const Vec3& p : mesh.positions) split += p.norm() / double(mesh.positions.size());
  for (const Vec3& p : mesh.positions) {
    if ((p.norm() > split) != outer_half) continue;
    sum += p.norm();
    count += 1.0;
  }
  return sum / count;
}

}  // namespace

TEST(SkullInput, CtBoneSurfaceLiesAtTheMeasuredHalfMaximumHeight) {
  const double outer = 45.0, inner = 35.0;
  const ScalarGrid ct = blurred_shell_ct(outer, inner);
  SkullInputOptions options;
  options.min_triangles = 0;
  options.half_maximum_height = true;
  const Skull skull = skull_from_volume(ct, "shell CT", options);
  ASSERT_TRUE(skull.iso_value && skull.seed_iso_value);
  EXPECT_EQ(*skull.seed_iso_value, 1150.0);
  EXPECT_NEAR(*skull.iso_value, 1400.0, 10.0);  // half-way between bone and soft tissue
  EXPECT_GT(skull.threshold_profiles, 200u);
  // The outer surface (the one a tissue depth is measured from) on the bone's edge; 1150 lies 0.9 mm outside it.
  EXPECT_NEAR(mean_radius(skull.mesh, true), outer, 0.15);
  bool noted = false;
  for (const std::string& n : skull.notes) noted = noted || n.find("half-maximum height") != std::string::npos;
  EXPECT_TRUE(noted);
  // Off, or an iso-value given: the surface stays at it.
  options.half_maximum_height = false;
  const Skull fixed = skull_from_volume(ct, "shell CT", options);
  EXPECT_EQ(*fixed.iso_value, 1150.0);
  EXPECT_FALSE(fixed.seed_iso_value);
  EXPECT_GT(mean_radius(fixed.mesh, true) - outer, 0.6);
  options.half_maximum_height = true;
  options.bone_iso_value = 1300.0;
  const Skull given = skull_from_volume(ct, "shell CT", options);
  EXPECT_EQ(*given.iso_value, 1300.0);
  EXPECT_FALSE(given.seed_iso_value);
}

// The built-in CT phantom (2 mm voxels, each edge blurred over about a voxel, noise 20): its bone surface by default
// lies on the phantom's bone, closer than the 126 HU iso-surface, which lies outside it.
TEST(SkullInput, CtPhantomBoneSurfaceLiesOnThePhantomsBone) {
  const ScalarGrid ct = make_ct_head_phantom();
  const auto truth = [](const Vec3& p) {
    return std::max(ct_phantom_bone_distance(p), ct_phantom_skin_distance(p) + 2.0);  // as the phantom's CT
  };
  const auto distances = [&](const TriMesh& mesh, double& mean_abs) {
    double sum = 0.0, sum_abs = 0.0;
    for (const Vec3& p : mesh.positions) {
      const double d = truth(p);
      sum += d;
      sum_abs += std::abs(d);
    }
    mean_abs = sum_abs / double(mesh.positions.size());
    return sum / double(mesh.positions.size());
  };
  SkullInputOptions options;
  options.min_triangles = 0;
  options.half_maximum_height = true;
  const Skull measured = skull_from_volume(ct, "CT phantom", options);
  options.bone_iso_value = 1150.0;
  const Skull fixed = skull_from_volume(ct, "CT phantom", options);
  double abs_measured = 0.0, abs_fixed = 0.0;
  const double signed_measured = distances(measured.mesh, abs_measured);
  const double signed_fixed = distances(fixed.mesh, abs_fixed);
  std::printf(
      "CT phantom bone at %.1f: signed %+.3f mm, mean |d| %.3f mm; at 1150: signed %+.3f mm, mean |d| %.3f mm\n",
      *measured.iso_value, signed_measured, abs_measured, signed_fixed, abs_fixed);
  EXPECT_NEAR(*measured.iso_value, 1400.0, 15.0);  // soft tissue 1000, bone 1800
  EXPECT_GT(signed_fixed, 0.5);                    // 1150 lies outside the bone
  EXPECT_LT(std::abs(signed_measured), 0.25);
  EXPECT_LT(abs_measured, 0.6 * abs_fixed);
}
