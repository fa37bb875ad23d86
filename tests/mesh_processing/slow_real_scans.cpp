#include <gtest/gtest.h>

#include <chrono>
#include <iostream>

#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "mesh_processing/decimate.hpp"
#include "mesh_processing/obj_reader.hpp"
#include "mesh_processing/remesh_isotropic.hpp"
#include "mesh_processing/repair_mesh.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Repairs a real scan, prints the report and timing, and checks the result is a closed, oriented,
/// manifold surface whose volume is close to the input's (for inputs that were closed already).
void repair_scan(const std::filesystem::path& path, bool closed_input) {
  TriMesh mesh = test::read_obj_positions(path.string());
  const double volume_before = enclosed_volume(mesh);
  const auto start = std::chrono::steady_clock::now();
  const RepairReport report = repair_mesh(mesh);
  const double seconds = seconds_since(start);
  std::cout << path.filename().string() << ": " << report.before.summary() << " -> " << report.after.summary() << " in "
            << seconds << " s\n"
            << report.summary() << "\n";
  EXPECT_TRUE(report.manifold()) << report.summary();
  EXPECT_TRUE(report.closed()) << report.summary();
  EXPECT_TRUE(report.after.is_oriented());
  EXPECT_GT(enclosed_volume(mesh), 0.0);
  if (closed_input) {
    EXPECT_NEAR(enclosed_volume(mesh), std::abs(volume_before), 1e-3 * std::abs(volume_before));
  }
}

}  // namespace

TEST(RealScans, RepairHandClosed) {
  FORENSIM_REQUIRE_DATA(path, "hand-mesh/hand_closed.obj");
  repair_scan(path, true);
}

TEST(RealScans, RepairHandLowresOpenWrist) {
  FORENSIM_REQUIRE_DATA(path, "hand-mesh/hand_lowres.obj");
  repair_scan(path, false);
}

TEST(RealScans, RepairDemosthenesOpenBase) {
  FORENSIM_REQUIRE_DATA(path, "head-busts/demosthenes-low-res.obj");
  repair_scan(path, false);
}

TEST(RealScans, RepairNefertiti) {
  FORENSIM_REQUIRE_DATA(path, "head-busts/nefertiti-lowres.obj");
  repair_scan(path, true);
}

TEST(RealScans, RepairSkull) {
  FORENSIM_REQUIRE_DATA(path, "skull-mesh/skull.obj");
  repair_scan(path, true);
}

TEST(RealScans, DecimateAndRemeshSkull) {
  FORENSIM_REQUIRE_DATA(path, "skull-mesh/skull.obj");
  const TriMesh skull = test::read_obj_positions(path.string());
  auto start = std::chrono::steady_clock::now();
  const TriMesh coarse = decimate(skull, 20000);
  std::cout << "decimate skull " << skull.triangle_count() << " -> " << coarse.triangle_count() << " triangles in "
            << seconds_since(start) << " s; " << check_topology(coarse).summary() << "\n";
  EXPECT_LE(coarse.triangle_count(), 20000u);
  EXPECT_GE(coarse.triangle_count(), 19990u);
  EXPECT_NEAR(enclosed_volume(coarse), enclosed_volume(skull), 0.02 * enclosed_volume(skull));

  start = std::chrono::steady_clock::now();
  const TriMesh remeshed = remesh_isotropic(coarse, 0.15, 3);  // skull ~13.9 units tall
  std::cout << "remesh skull at 0.15 -> " << remeshed.triangle_count() << " triangles in " << seconds_since(start)
            << " s; " << check_topology(remeshed).summary() << "\n";
  EXPECT_NEAR(enclosed_volume(remeshed), enclosed_volume(coarse), 0.02 * enclosed_volume(coarse));
  EXPECT_TRUE(check_topology(remeshed).is_manifold());
}

TEST(RealScans, DamagedHandIsRestored) {
  FORENSIM_REQUIRE_DATA(path, "hand-mesh/hand_closed.obj");
  const TriMesh hand = test::read_obj_positions(path.string());
  const double volume = enclosed_volume(hand);
  // Damage it as scans arrive: three holes, duplicated and flipped triangles, a soup-like duplicate vertex.
  std::vector<bool> keep(hand.triangle_count(), true);
  for (const std::size_t f : {100u, 101u, 102u, 5000u, 5001u, 12000u}) keep[f] = false;
  TriMesh damaged = extract_triangles(hand, keep);
  for (std::size_t f = 0; f < damaged.triangle_count(); f += 97)
    std::swap(damaged.triangles[f][0], damaged.triangles[f][1]);
  for (std::size_t f = 0; f < 50; ++f) damaged.triangles.push_back(damaged.triangles[3 * f + 7]);
  damaged.positions.push_back(damaged.positions[damaged.triangles[200][0]]);
  damaged.triangles[200][0] = static_cast<Index>(damaged.positions.size() - 1);
  const auto start = std::chrono::steady_clock::now();
  const RepairReport report = repair_mesh(damaged);
  std::cout << "damaged hand repaired in " << seconds_since(start) << " s\n" << report.summary() << "\n";
  EXPECT_TRUE(report.closed() && report.manifold() && report.after.is_oriented()) << report.summary();
  EXPECT_EQ(report.duplicate_triangles_removed, 50u);
  EXPECT_GE(report.triangles_flipped, 165u);  // every 97th of 15976 was flipped
  EXPECT_LE(report.triangles_flipped, 200u);
  EXPECT_GE(report.holes_filled, 1u);
  EXPECT_NEAR(enclosed_volume(damaged), volume, 0.01 * volume);
}
