#include <gtest/gtest.h>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "mesh_processing/repair_mesh.hpp"

using namespace forensim;

namespace {

void expect_closed_manifold_outward(const TriMesh& mesh, const RepairReport& report) {
  const TopologyReport t = check_topology(mesh);
  EXPECT_TRUE(t.is_closed()) << report.summary();
  EXPECT_TRUE(t.is_manifold()) << report.summary();
  EXPECT_TRUE(t.is_oriented()) << report.summary();
  EXPECT_TRUE(report.closed());
  EXPECT_TRUE(report.manifold());
  EXPECT_EQ(t.degenerate_triangle_count, 0u);
  EXPECT_EQ(t.isolated_vertex_count, 0u);
  EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
}

}  // namespace

TEST(RepairMesh, BoxWithMissingQuadAndDuplicatesBecomesClosed) {
  const TriMesh box = make_box_mesh(Vec3(0, 0, 0), Vec3(2, 3, 4), 3);
  const double volume = enclosed_volume(box);
  std::vector<bool> keep(box.triangle_count(), true);
  keep[4] = keep[5] = false;  // one quad of the first face
  TriMesh broken = extract_triangles(box, keep);
  broken.normals.clear();
  broken.triangles.push_back(broken.triangles[10]);  // exact duplicate
  Tri reversed = broken.triangles[20];
  std::swap(reversed[1], reversed[2]);
  broken.triangles.push_back(reversed);                                   // duplicate with the other orientation
  broken.triangles.push_back({3, 3, 7});                                  // repeats a vertex
  broken.positions.push_back(Vec3(9, 9, 9));                              // isolated vertex
  broken.positions.push_back(broken.positions[broken.triangles[30][0]]);  // exact duplicate position
  broken.triangles[30][0] = static_cast<Index>(broken.positions.size() - 1);
  ASSERT_FALSE(check_topology(broken).is_closed());

  const RepairReport report = repair_mesh(broken);
  expect_closed_manifold_outward(broken, report);
  EXPECT_EQ(report.duplicate_triangles_removed, 2u);
  EXPECT_GE(report.degenerate_triangles_removed, 1u);
  EXPECT_GE(report.isolated_vertices_removed, 1u);
  EXPECT_GE(report.vertices_merged, 1u);
  EXPECT_EQ(report.holes_found, 1u);
  EXPECT_EQ(report.holes_filled, 1u);
  EXPECT_GT(report.triangles_added, 0u);
  EXPECT_NEAR(enclosed_volume(broken), volume, 0.01 * volume) << report.summary();
  EXPECT_FALSE(report.summary().empty());
}

TEST(RepairMesh, FlippedTrianglesAreFixedAndOutward) {
  for (const int flipped : {0, 7}) {  // triangle 0 seeds CGAL's orientation pass: the rest flips, then outward
    TriMesh box = make_box_mesh(Vec3(-1, -1, -1), Vec3(1, 2, 1), 2);
    const double volume = enclosed_volume(box);
    std::swap(box.triangles[flipped][0], box.triangles[flipped][1]);
    ASSERT_FALSE(check_topology(box).is_oriented());
    const RepairReport report = repair_mesh(box);
    expect_closed_manifold_outward(box, report);
    EXPECT_GE(report.triangles_flipped, 1u);
    EXPECT_NEAR(enclosed_volume(box), volume, 1e-9) << "flipped " << flipped;
  }
}

TEST(RepairMesh, InsideOutSphereIsTurnedOutward) {
  TriMesh sphere = make_icosphere(Vec3(1, 2, 3), 2.0, 3);
  const double volume = enclosed_volume(sphere);
  for (Tri& t : sphere.triangles) std::swap(t[1], t[2]);
  ASSERT_LT(enclosed_volume(sphere), 0.0);
  const RepairReport report = repair_mesh(sphere);
  expect_closed_manifold_outward(sphere, report);
  EXPECT_NEAR(enclosed_volume(sphere), volume, 1e-9);
  EXPECT_EQ(report.triangles_flipped, sphere.triangle_count());
}

TEST(RepairMesh, SphereHoleIsFilledAndFaired) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 10.0, 4);
  const double volume = enclosed_volume(sphere);
  // Remove a cap of triangles around +z: a hole of several rings.
  std::vector<bool> keep(sphere.triangle_count(), true);
  for (std::size_t f = 0; f < sphere.triangle_count(); ++f) {
    const Tri& t = sphere.triangles[f];
    const double z = (sphere.positions[t[0]] + sphere.positions[t[1]] + sphere.positions[t[2]]).z() / 3.0;
    if (z > 9.0) keep[f] = false;
  }
  TriMesh holed = extract_triangles(sphere, keep);
  const double cap = 3.14159265358979 * 1.0 * 1.0 * (3 * 10.0 - 1.0) / 3.0;  // spherical cap of height 1
  const RepairReport report = repair_mesh(holed);
  expect_closed_manifold_outward(holed, report);
  EXPECT_EQ(report.holes_filled, 1u);
  // Fairing bulges the patch towards the sphere: most of the cap's volume comes back.
  EXPECT_GT(enclosed_volume(holed), volume - 0.5 * cap) << report.summary();
  EXPECT_LT(enclosed_volume(holed), volume + 0.1 * cap);
}

TEST(RepairMesh, LargeHoleIsLeftOpenAndReported) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 1.0, 3);
  std::vector<bool> keep(sphere.triangle_count(), true);
  for (std::size_t f = 0; f < sphere.triangle_count(); ++f) {
    const Tri& t = sphere.triangles[f];
    if ((sphere.positions[t[0]] + sphere.positions[t[1]] + sphere.positions[t[2]]).z() > 0.0) keep[f] = false;
  }
  TriMesh bowl = extract_triangles(sphere, keep);
  RepairOptions options;
  options.max_hole_edges = 10;
  const RepairReport report = repair_mesh(bowl, options);
  EXPECT_EQ(report.holes_skipped, 1u);
  EXPECT_EQ(report.holes_filled, 0u);
  EXPECT_FALSE(report.closed());
  EXPECT_TRUE(report.manifold());
  EXPECT_FALSE(report.notes.empty());
  // A diameter limit skips it too.
  TriMesh bowl2 = extract_triangles(sphere, keep);
  RepairOptions by_size;
  by_size.max_hole_diameter = 0.5;
  EXPECT_EQ(repair_mesh(bowl2, by_size).holes_skipped, 1u);
}

TEST(RepairMesh, UnweldedSoupIsWeldedWithTolerance) {
  // Every triangle with its own three vertices, slightly perturbed: a scan exported as a triangle soup.
  const TriMesh box = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2);
  TriMesh soup;
  for (const Tri& t : box.triangles) {
    Tri u;
    for (int k = 0; k < 3; ++k) {
      u[k] = static_cast<Index>(soup.positions.size());
      soup.positions.push_back(box.positions[t[k]] + Vec3::Constant(1e-7 * (k + 1)));
    }
    soup.triangles.push_back(u);
  }
  RepairOptions options;
  options.merge_distance = 1e-4;
  const RepairReport report = repair_mesh(soup, options);
  expect_closed_manifold_outward(soup, report);
  EXPECT_EQ(soup.vertex_count(), box.vertex_count());
  EXPECT_NEAR(enclosed_volume(soup), 1.0, 1e-5);
}

TEST(RepairMesh, NonManifoldEdgeIsSplit) {
  // Two closed tetrahedra sharing one edge: that edge has four triangles.
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0.2}, {0.5, 0.3, 1}, {0.5, -1, 0.2}, {0.5, -0.3, -1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 1, 4}, {0, 5, 1}, {1, 5, 4}, {0, 4, 5}};
  ASSERT_GT(check_topology(m).nonmanifold_edge_count, 0u);
  const RepairReport report = repair_mesh(m);
  EXPECT_GT(report.vertices_split_nonmanifold, 0u);
  EXPECT_TRUE(report.manifold()) << report.summary();
  EXPECT_TRUE(report.closed()) << report.summary();
  EXPECT_EQ(m.triangle_count(), 8u);
}

TEST(RepairMesh, RejectsBadInput) {
  TriMesh m = make_icosphere(Vec3::Zero(), 1.0, 0);
  m.triangles[0][0] = 1000;
  EXPECT_THROW(repair_mesh(m), InputError);
  TriMesh ok = make_icosphere(Vec3::Zero(), 1.0, 0);
  RepairOptions options;
  options.merge_distance = -1.0;
  EXPECT_THROW(repair_mesh(ok, options), InputError);
  TriMesh empty;
  const RepairReport report = repair_mesh(empty);
  EXPECT_EQ(empty.triangle_count(), 0u);
  EXPECT_EQ(report.holes_found, 0u);
}

TEST(RepairMesh, SelfIntersectionsAreReported) {
  TriMesh one = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 1);
  one.normals.clear();
  RepairOptions options;
  options.check_self_intersections = true;
  TriMesh single = one;
  const RepairReport clean = repair_mesh(single, options);
  EXPECT_TRUE(clean.self_intersections_checked);
  EXPECT_FALSE(clean.self_intersecting);
  // Two interpenetrating boxes.
  TriMesh two = one;
  const Index offset = static_cast<Index>(two.positions.size());
  for (const Vec3& p : one.positions) two.positions.push_back(p + Vec3(0.5, 0.5, 0.5));
  for (const Tri& t : one.triangles) two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const RepairReport crossing = repair_mesh(two, options);
  EXPECT_TRUE(crossing.self_intersecting);
  EXPECT_TRUE(crossing.closed());
  EXPECT_FALSE(crossing.notes.empty());
}
