#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/error.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "geometry/vertex_neighbours.hpp"

using namespace forensim;

// Every vertex's list is exactly the set of vertices it shares a triangle edge with, each once, and the
// relation is symmetric; the lists hold every unique edge twice.
TEST(VertexNeighbours, ListsEachEdgeNeighbourOnce) {
  const TriMesh box = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 3);
  const std::size_t n = box.positions.size();
  const VertexNeighbours adjacency = vertex_neighbours(box.triangles, n);
  ASSERT_EQ(adjacency.start.size(), n + 1);
  EXPECT_EQ(adjacency.index.size(), 2 * unique_edges(box.triangles).size());
  std::vector<std::set<Index>> expected(n);
  for (const Tri& t : box.triangles)
    for (int k = 0; k < 3; ++k) {
      expected[std::size_t(t[k])].insert(t[(k + 1) % 3]);
      expected[std::size_t(t[(k + 1) % 3])].insert(t[k]);
    }
  for (std::size_t v = 0; v < n; ++v) {
    const std::set<Index> listed(adjacency.index.begin() + std::ptrdiff_t(adjacency.start[v]),
                                 adjacency.index.begin() + std::ptrdiff_t(adjacency.start[v + 1]));
    EXPECT_EQ(listed.size(), adjacency.degree(v)) << "vertex " << v << " lists a neighbour twice";
    EXPECT_EQ(listed, expected[v]) << "vertex " << v;
  }
}

TEST(VertexNeighbours, VertexOnNoTriangleHasNone) {
  const std::vector<Tri> triangles = {{0, 1, 2}};
  const VertexNeighbours adjacency = vertex_neighbours(triangles, 4);
  EXPECT_EQ(adjacency.degree(0), 2u);
  EXPECT_EQ(adjacency.degree(3), 0u);
}

TEST(VertexNeighbours, IndexOutsideTheMeshIsRefused) {
  EXPECT_THROW(vertex_neighbours({{0, 1, 3}}, 3), InputError);
  EXPECT_THROW(vertex_neighbours({{0, -1, 2}}, 3), InputError);
}
