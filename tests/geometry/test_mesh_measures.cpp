#include <gtest/gtest.h>

#include <numbers>

#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

TEST(MeshMeasures, BoxAreaVolumeAndBounds) {
  const TriMesh box = make_box_mesh(Vec3(-1, 0, 2), Vec3(2, 4, 7), 3);
  EXPECT_EQ(box.vertex_count(), 6u * 9 + 2);
  EXPECT_EQ(box.triangle_count(), 12u * 9);
  EXPECT_NEAR(surface_area(box), 2 * (3 * 4 + 3 * 5 + 4 * 5), 1e-9);
  EXPECT_NEAR(enclosed_volume(box), 3 * 4 * 5, 1e-9);
  const BoundingBox bb = bounding_box(box.positions);
  EXPECT_TRUE(bb.min.isApprox(Vec3(-1, 0, 2)));
  EXPECT_TRUE(bb.max.isApprox(Vec3(2, 4, 7)));
}

TEST(MeshMeasures, IcosphereConvergesToSphere) {
  double previous_error = 1e9;
  for (int s = 1; s <= 4; ++s) {
    const TriMesh sphere = make_icosphere(Vec3(1, 2, 3), 2.0, s);
    const double error = std::abs(enclosed_volume(sphere) - 4.0 / 3.0 * std::numbers::pi * 8.0);
    EXPECT_LT(error, previous_error / 3.0);  // second-order: error quarters with each subdivision
    previous_error = error;
  }
}

TEST(MeshMeasures, VertexNormalsOfSpherePointOutward) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 1.0, 3);
  const auto normals = vertex_normals(sphere);
  for (std::size_t v = 0; v < normals.size(); ++v) EXPECT_GT(normals[v].dot(sphere.positions[v]), 0.99);
}

TEST(MeshMeasures, TetBoxVolumeAndOrientation) {
  const TetMesh tets = make_box_tet_mesh(Vec3(0, 0, 0), Vec3(2, 3, 4), 3, 2, 5);
  EXPECT_EQ(tets.tet_count(), 6u * 30);
  EXPECT_NEAR(tet_mesh_volume(tets), 24.0, 1e-9);
  for (const Tet& t : tets.tets) {
    EXPECT_GT(tet_signed_volume(tets.positions[t[0]], tets.positions[t[1]], tets.positions[t[2]], tets.positions[t[3]]),
              0);
  }
}
