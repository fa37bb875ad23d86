// Skull/skin violation counts on shapes with known answers.
#include "craniofacial/skull_skin_violations.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

TEST(SkullSkinViolations, NestedSpheresHaveNone) {
  const TriMesh skin = make_icosphere(Vec3::Zero(), 100.0, 4);
  const TriMesh skull = make_icosphere(Vec3::Zero(), 94.0, 4);
  const SkullSkinViolations v = count_skull_skin_violations(skull, skin);
  EXPECT_EQ(v.total(), 0u);
  EXPECT_EQ(v.skull_vertex_count, skull.positions.size());
}

TEST(SkullSkinViolations, CountsAProtrudingSkullAndMeasuresIt) {
  const TriMesh skin = make_icosphere(Vec3::Zero(), 100.0, 4);
  // A skull sphere shifted 10 mm along +x: its cap beyond x = 100 - ... pierces the skin by up to 4 mm.
  const TriMesh skull = make_icosphere(Vec3(10, 0, 0), 94.0, 4);
  const SkullSkinViolations v = count_skull_skin_violations(skull, skin);
  std::size_t expected = 0;
  for (const Vec3& p : skull.positions) expected += p.norm() > 100.0 + 0.5 ? 1 : 0;
  EXPECT_GE(v.skull_outside_skin, expected);
  EXPECT_GT(v.skull_outside_skin, 0u);
  EXPECT_NEAR(v.max_skull_protrusion_mm, 4.0, 0.5);
  EXPECT_EQ(v.skull_outside_skin, v.skull_vertices_outside.size());
  for (const std::size_t i : v.skull_vertices_outside) EXPECT_GT(skull.positions[i].norm(), 99.0);
  // And the skin on that side lies inside the skull.
  EXPECT_GT(v.skin_inside_skull, 0u);
  for (const std::size_t i : v.skin_vertices_inside) EXPECT_GT(skin.positions[i].x(), 0.0);
  EXPECT_LT(v.max_skin_intrusion_mm, 4.5);
}

TEST(SkullSkinViolations, RejectsEmptyMeshes) {
  const TriMesh sphere = make_icosphere(Vec3::Zero(), 10.0, 2);
  EXPECT_THROW(count_skull_skin_violations(TriMesh{}, sphere), InputError);
  EXPECT_THROW(count_skull_skin_violations(sphere, TriMesh{}), InputError);
}
