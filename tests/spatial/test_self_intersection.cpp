#include "spatial/self_intersection.hpp"

#include <gtest/gtest.h>

#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

/// `a` and `b` as one mesh.
TriMesh merged(const TriMesh& a, const TriMesh& b) {
  TriMesh out = a;
  const auto offset = static_cast<Index>(a.positions.size());
  out.positions.insert(out.positions.end(), b.positions.begin(), b.positions.end());
  for (Tri t : b.triangles) {
    for (Index& v : t) v += offset;
    out.triangles.push_back(t);
  }
  return out;
}

}  // namespace

// A sphere is embedded; two overlapping spheres in one mesh cross along a circle; two apart do not; a sphere with
// one vertex pushed through to the far side crosses itself.
TEST(SelfIntersection, CountsCrossingsOfEmbeddedAndFoldedMeshes) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 1.0, 3);
  EXPECT_EQ(self_intersection_count(sphere), 0u);
  EXPECT_EQ(self_intersection_count(merged(sphere, make_icosphere(Vec3(3.0, 0.0, 0.0), 1.0, 3))), 0u);
  // Overlapping: every edge crossing the circle of intersection counts, so at least one per triangle around it.
  EXPECT_GT(self_intersection_count(merged(sphere, make_icosphere(Vec3(1.0, 0.0, 0.0), 1.0, 3))), 20u);
  TriMesh folded = sphere;
  folded.positions[0] = -1.5 * folded.positions[0];  // through the sphere and out of the far side
  EXPECT_GT(self_intersection_count(folded), 0u);
}
