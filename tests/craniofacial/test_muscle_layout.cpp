// Muscle layout grids and their shapes under a skin.
#include "craniofacial/muscle_layout.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

TEST(MuscleLayout, TheTwentyFourMusclesAreMirroredPairs) {
  const auto layouts = head_phantom_muscle_layouts(4, 7);
  ASSERT_EQ(layouts.size(), 24u);
  std::set<std::string> names;
  for (const MuscleLayout& m : layouts) {
    names.insert(m.name);
    EXPECT_EQ(m.grid.size(), 28u);
  }
  EXPECT_EQ(names.size(), 24u);
  for (const MuscleLayout& m : layouts) {
    if (m.name.size() < 2 || m.name.substr(m.name.size() - 2) != "_L") continue;
    const std::string right = m.name.substr(0, m.name.size() - 2) + "_R";
    const auto it =
        std::find_if(layouts.begin(), layouts.end(), [&](const MuscleLayout& o) { return o.name == right; });
    ASSERT_NE(it, layouts.end()) << right;
    for (std::size_t i = 0; i < m.grid.size(); ++i) {
      // Same points mirrored (fibre order across the muscle may reverse).
      double best = 1e9;
      for (const Vec3& q : it->grid) best = std::min(best, (Vec3(-q.x(), q.y(), q.z()) - m.grid[i]).norm());
      ASSERT_LT(best, 1e-9) << m.name;
    }
  }
  EXPECT_THROW(head_phantom_muscle_layouts(1, 7), InputError);
  EXPECT_THROW(head_phantom_muscle_layouts(4, 2), InputError);
}

TEST(MuscleLayout, ShapesLieTheirThicknessUnderTheSkin) {
  constexpr double radius = 100.0;
  TriMesh skin = make_icosphere(Vec3::Zero(), radius, 5);
  compute_normals(skin);
  MuscleLayout linear;
  linear.name = "test_linear";
  linear.fibre_count = 3;
  linear.samples_per_fibre = 5;
  linear.thickness_mm = 4.0;
  for (int f = 0; f < 3; ++f) {
    for (int s = 0; s < 5; ++s) linear.grid.push_back(Vec3(10.0 * f, 10.0 * s, 120.0));  // above the sphere
  }
  MuscleLayout ring = linear;
  ring.name = "test_ring";
  ring.kind = MuscleKind::sphincter;
  const auto shapes = shape_muscles({linear, ring}, skin);
  ASSERT_EQ(shapes.size(), 2u);
  for (const MuscleShape& s : shapes) {
    ASSERT_EQ(s.fibre_points.size(), 15u);
    for (std::size_t i = 0; i < 15; ++i) {
      EXPECT_NEAR(s.skin_points[i].norm(), radius, 0.1);          // on the (faceted) sphere
      EXPECT_NEAR(s.fibre_points[i].norm(), radius - 4.0, 0.15);  // under it along the normal
    }
    ASSERT_EQ(s.fibre_lengths_mm.size(), 3u);
  }
  // A closed ring is longer than the open fibre through the same points by its closing segment.
  for (int f = 0; f < 3; ++f) {
    const auto& a = shapes[0].fibre_points;
    const double closing = (a[static_cast<std::size_t>(f * 5)] - a[static_cast<std::size_t>(f * 5 + 4)]).norm();
    EXPECT_NEAR(shapes[1].fibre_lengths_mm[static_cast<std::size_t>(f)],
                shapes[0].fibre_lengths_mm[static_cast<std::size_t>(f)] + closing, 1e-9);
  }
  MuscleLayout broken = linear;
  broken.grid.pop_back();
  EXPECT_THROW(shape_muscles({broken}, skin), InputError);
  MuscleLayout nan = linear;
  nan.grid[2].x() = std::nan("");
  EXPECT_THROW(shape_muscles({nan}, skin), InputError);
  EXPECT_THROW(shape_muscles({linear}, TriMesh{}), InputError);
}
