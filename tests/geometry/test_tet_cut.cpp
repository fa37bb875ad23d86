#include "geometry/tet_cut.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

TEST(TetCut, KeepsTheHalfBehindThePlaneWithLabels) {
  TetMesh box = make_box_tet_mesh(Vec3::Zero(), Vec3(10, 10, 10), 4, 4, 4);
  for (std::size_t t = 0; t < box.tet_count(); ++t) box.tet_labels.push_back(static_cast<int>(t % 2));
  const TetMesh half = tets_behind_plane(box, Vec3(5, 5, 5), Vec3(0, 0, 2));
  // The plane runs between cell layers: exactly half the volume stays, every kept centroid below it.
  EXPECT_NEAR(tet_mesh_volume(half), 500.0, 1e-9);
  EXPECT_EQ(half.positions, box.positions);
  ASSERT_EQ(half.tet_labels.size(), half.tet_count());
  for (std::size_t t = 0; t < half.tet_count(); ++t) {
    double z = 0.0;
    for (Index v : half.tets[t]) z += half.positions[static_cast<std::size_t>(v)].z() / 4.0;
    EXPECT_LE(z, 5.0);
  }
  EXPECT_THROW(tets_behind_plane(box, Vec3::Zero(), Vec3::Zero()), InputError);
}
