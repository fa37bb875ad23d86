#include <gtest/gtest.h>

#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_boundary.hpp"

using namespace forensim;

TEST(Topology, ClosedBoxIsClosedManifoldOriented) {
  const TopologyReport r = check_topology(make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2));
  EXPECT_TRUE(r.is_closed());
  EXPECT_TRUE(r.is_manifold());
  EXPECT_TRUE(r.is_oriented());
  EXPECT_EQ(r.component_count, 1u);
  EXPECT_EQ(r.edge_count, 3u * 12 * 4 / 2);
}

TEST(Topology, RemovingTrianglesOpensHoles) {
  TriMesh box = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 3);
  std::vector<bool> keep(box.triangle_count(), true);
  keep[0] = keep[1] = false;  // one quad: one hole of 4 edges
  keep[40] = false;           // one far-away triangle: a second hole of 3 edges
  const TopologyReport r = check_topology(extract_triangles(box, keep));
  EXPECT_FALSE(r.is_closed());
  EXPECT_EQ(r.boundary_edge_count, 7u);
  EXPECT_EQ(r.boundary_loop_count, 2u);
}

TEST(Topology, FlippedTriangleIsMisoriented) {
  TriMesh box = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 1);
  std::swap(box.triangles[3][0], box.triangles[3][1]);
  EXPECT_FALSE(check_topology(box).is_oriented());
}

TEST(Topology, ThreeTrianglesOnOneEdgeAreNonManifold) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  EXPECT_EQ(check_topology(m).nonmanifold_edge_count, 1u);
}

TEST(Topology, TwoConesTouchingAtAVertexAreNonManifoldVertex) {
  TriMesh a = make_icosphere(Vec3::Zero(), 1.0, 0);
  TriMesh b = make_icosphere(Vec3(2, 0, 0), 1.0, 0);
  // Share one vertex: move b's vertex 0 onto a's vertex 0 and merge indices.
  TriMesh both = a;
  const Index off = static_cast<Index>(a.positions.size());
  for (const Vec3& p : b.positions) both.positions.push_back(p);
  for (Tri t : b.triangles) {
    for (Index& i : t) i = (i == 0) ? 0 : i + off;
    both.triangles.push_back(t);
  }
  const TopologyReport r = check_topology(both);
  EXPECT_EQ(r.nonmanifold_vertex_count, 1u);
  EXPECT_EQ(r.nonmanifold_edge_count, 0u);
}

TEST(Topology, ComponentsAndLargest) {
  TriMesh a = make_icosphere(Vec3::Zero(), 1.0, 2);
  const TriMesh b = make_icosphere(Vec3(5, 0, 0), 2.0, 2);
  const Index off = static_cast<Index>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (Tri t : b.triangles) a.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  a.normals.clear();
  int count = 0;
  (void)triangle_components(a, &count);
  EXPECT_EQ(count, 2);
  const TriMesh largest = keep_largest_components(a, 1);
  EXPECT_NEAR(enclosed_volume(largest), enclosed_volume(b), 1e-9);
}

TEST(Topology, WeldMergesNearDuplicates) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1e-7, 0, 0}, {0, 1, 1e-7}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  std::vector<Index> remap;
  const TriMesh w = weld_vertices(m, 1e-5, &remap);
  EXPECT_EQ(w.vertex_count(), 4u);
  EXPECT_EQ(remap[3], remap[0]);
  EXPECT_EQ(remap[4], remap[2]);
}

TEST(TetBoundary, BoxBoundaryIsClosedWithOutwardFacesAndRightArea) {
  const TetMesh tets = make_box_tet_mesh(Vec3::Zero(), Vec3(1, 2, 3), 2, 3, 4);
  std::vector<TetFace> source;
  const TriMesh surface = tet_boundary_mesh(tets, -1, &source);
  EXPECT_EQ(surface.triangle_count(), 2u * 2 * (2 * 3 + 2 * 4 + 3 * 4));
  const TopologyReport r = check_topology(surface);
  EXPECT_TRUE(r.is_closed() && r.is_manifold() && r.is_oriented());
  EXPECT_NEAR(enclosed_volume(surface), 6.0, 1e-9);
  EXPECT_NEAR(surface_area(surface), 2 * (2 + 3 + 6), 1e-9);
  // Each face comes from the tet and local face it names.
  for (std::size_t f = 0; f < source.size(); ++f) {
    const Tet& t = tets.tets[source[f].tet];
    for (int c = 0; c < 3; ++c) EXPECT_EQ(source[f].vertices[c], t[tet_local_faces[source[f].local_face][c]]);
  }
}

TEST(TetBoundary, RegionInterfaceOfLabelledBlock) {
  TetMesh tets = make_box_tet_mesh(Vec3::Zero(), Vec3(4, 4, 4), 4, 4, 4);
  tets.tet_labels.resize(tets.tet_count());
  double inner = 0;
  for (std::size_t t = 0; t < tets.tet_count(); ++t) {
    Vec3 c = Vec3::Zero();
    for (Index i : tets.tets[t]) c += tets.positions[i] / 4.0;
    const bool bone = (c.array() > 1.0).all() && (c.array() < 3.0).all();
    tets.tet_labels[t] = bone ? tissue_bone : tissue_flesh;
  }
  const TriMesh bone = tet_boundary_mesh(tets, tissue_bone);
  inner = enclosed_volume(bone);
  EXPECT_NEAR(inner, 8.0, 1e-9);
  EXPECT_NEAR(tet_mesh_volume(tets, tissue_bone), 8.0, 1e-9);
  EXPECT_TRUE(check_topology(bone).is_closed());
}

TEST(TetBoundary, NeighborsAreSymmetric) {
  const TetMesh tets = make_box_tet_mesh(Vec3::Zero(), Vec3::Ones(), 2, 2, 2);
  const auto nb = tet_neighbors(tets);
  std::size_t boundary = 0;
  for (std::size_t t = 0; t < nb.size(); ++t) {
    for (int f = 0; f < 4; ++f) {
      if (nb[t][f] < 0) {
        ++boundary;
        continue;
      }
      const auto& other = nb[nb[t][f]];
      EXPECT_NE(std::find(other.begin(), other.end(), static_cast<Index>(t)), other.end());
    }
  }
  EXPECT_EQ(boundary, tet_boundary_faces(tets).size());
}
