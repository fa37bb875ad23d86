#include <gtest/gtest.h>

#include "texture/uv_seams.hpp"

using namespace forensim;

namespace {
// Two triangles sharing the edge 1-2 of a unit square; `cut` gives the second its own UVs along the edge.
TriMesh square(bool cut) {
  TriMesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  m.triangles = {Tri{0, 1, 2}, Tri{1, 3, 2}};
  m.uvs = {Vec2(0, 0), Vec2(0.5, 0), Vec2(0, 0.5), Vec2(0.5, 0.5), Vec2(0.6, 0.0), Vec2(0.6, 0.5)};
  m.triangle_uvs = {Tri{0, 1, 2}, cut ? Tri{4, 3, 5} : Tri{1, 3, 2}};
  return m;
}
}  // namespace

TEST(UvSeams, FindsTheSharedEdgeOnlyWhereItsUvsDiffer) {
  EXPECT_TRUE(uv_seam_edges(square(false)).empty());
  const auto seams = uv_seam_edges(square(true));
  ASSERT_EQ(seams.size(), 1u);
  EXPECT_TRUE(seams[0].midpoint.isApprox(Vec3(0.5, 0.5, 0)));
  // The midpoint's UV on each side, nudged 2% into its own triangle.
  EXPECT_NEAR(seams[0].uv_a.x(), 0.25 + 0.02 * (0.0 - 0.25), 1e-12);
  EXPECT_NEAR(seams[0].uv_b.x(), 0.6 + 0.02 * (0.5 - 0.6), 1e-12);
  EXPECT_EQ(seams[0].triangle_a, 0u);
  EXPECT_EQ(seams[0].triangle_b, 1u);
  TriMesh no_uvs = square(true);
  no_uvs.triangle_uvs.clear();
  EXPECT_TRUE(uv_seam_edges(no_uvs).empty());
}
