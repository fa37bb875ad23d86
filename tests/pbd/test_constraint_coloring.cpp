#include "pbd/constraint_coloring.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "geometry/primitives.hpp"
#include "pbd/bending_constraint.hpp"
#include "pbd/stretch_constraint.hpp"

using namespace forensim;

TEST(ConstraintColoring, GroupsAreIndependentAndCoverEveryConstraintOnce) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 1.0, 3);
  const StretchConstraints s = make_stretch_constraints(sphere.positions, sphere.triangles, "sphere");
  const BendingConstraints b = make_bending_constraints(sphere.positions, sphere.triangles, "sphere");
  const std::size_t n = sphere.vertex_count();
  const ConstraintGroups sg = color_constraints(s.edge_vertices, n);
  const ConstraintGroups bg = color_constraints(b.quad_vertices, n);
  EXPECT_TRUE(groups_are_independent(sg, s.edge_vertices, n));
  EXPECT_TRUE(groups_are_independent(bg, b.quad_vertices, n));
  // The same constraints are coloured the same way every time.
  EXPECT_EQ(color_constraints(b.quad_vertices, n), bg);
  for (const auto& [groups, count] : {std::pair{sg, s.size()}, std::pair{bg, b.size()}}) {
    std::vector<int> seen(count, 0);
    for (const auto& g : groups)
      for (std::uint32_t c : g) ++seen[c];
    for (std::size_t c = 0; c < count; ++c) EXPECT_EQ(seen[c], 1) << "constraint " << c;
  }
  // Greedy colouring needs at most (max constraints per particle - 1) * arity + 1 colours; an icosphere vertex
  // has at most 6 edges.
  EXPECT_LE(sg.size(), 11u);
  // Putting two constraints with a shared particle in one group is detected.
  ConstraintGroups merged(1);
  merged[0] = {0, 1};
  const Index shared[] = {0, 1, 1, 2};
  EXPECT_FALSE(groups_are_independent(merged, shared, 2, 3));
}

TEST(ConstraintColoring, RejectsIndicesOutOfRange) {
  const Index bad[] = {0, 5};
  EXPECT_THROW(color_constraints(bad, 1, 2, 3), InputError);
}
