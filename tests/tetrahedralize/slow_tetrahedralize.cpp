// Slow suite: the property tests on the arm and head phantoms at a coarse size (the paper's Table 1 sizes are
// checked in tests/body/slow_phantom_model.cpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>

#include "core/error.hpp"
#include "core/random.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/primitives.hpp"
#include "geometry/tet_boundary.hpp"
#include "phantoms/phantom.hpp"
#include "phantoms/phantom_surface.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/winding_number.hpp"
#include "tet_model_tests.hpp"
#include "tetrahedralize/tet_quality.hpp"
#include "tetrahedralize/tetrahedralize.hpp"

using namespace forensim;

INSTANTIATE_TEST_SUITE_P(Phantoms, ModelTets, ::testing::Values("arm", "head"));

TEST(Tetrahedralize, SphereInSphereHasNestedLabels) {
  const TriMesh skin = make_icosphere(Vec3::Zero(), 30.0, 3);
  const TriMesh bone = make_icosphere(Vec3(3, 0, 0), 12.0, 3);
  TetrahedralizeOptions o;
  o.edge_length_mm = 8.0;
  TetrahedralizeReport r;
  const TetMesh m = tetrahedralize(skin, {bone}, o, &r);
  // Coarse for its size (volume accuracy is checked on finer models in ModelTets).
  EXPECT_NEAR(r.tet_volume_mm3, r.skin_volume_mm3, 0.03 * r.skin_volume_mm3);
  EXPECT_NEAR(r.bone_tet_volume_mm3, r.bone_volume_mm3, 0.05 * r.bone_volume_mm3);
  EXPECT_EQ(r.node_count, m.vertex_count());
  EXPECT_GT(r.bone_tet_count, 0u);
  EXPECT_NE(r.summary().find("tets"), std::string::npos);
}

TEST(Tetrahedralize, NodeTargetIsMetWithinTolerance) {
  const TriMesh skin = make_icosphere(Vec3::Zero(), 30.0, 3);
  TetrahedralizeOptions o;
  o.target_nodes = 1500;
  o.count_tolerance = 0.1;
  TetrahedralizeReport r;
  const TetMesh m = tetrahedralize(skin, {}, o, &r);
  EXPECT_NEAR(static_cast<double>(m.vertex_count()), 1500.0, 0.25 * 1500.0) << "edge " << r.edge_length_mm;
  EXPECT_TRUE(std::all_of(m.tet_labels.begin(), m.tet_labels.end(), [](int l) { return l == tissue_flesh; }));
}
