// Slow suite: real, imperfect inputs from ../shared/data through the tetrahedraliser: a hand scan (skin
// only), a bust with an open base (repaired), and a CT head with its skull as the bone region. Each must keep
// the enclosed volumes, give positive tets, and bound the boundary's distance to the input skin.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/tet_boundary.hpp"
#include "hausdorff.hpp"
#include "mesh_io/mesh_import.hpp"
#include "spatial/closest_point.hpp"
#include "support/test_support.hpp"
#include "tetrahedralize/tet_quality.hpp"
#include "tetrahedralize/tetrahedralize.hpp"
#include "volume/volume_reader.hpp"

using namespace forensim;

namespace {

// `from_ct`: meshed without the manifold criterion (tetrahedralize_ct), so the boundary is watertight but may
// pinch where the skull nearly touches itself, and the bound is the issue's: below the target edge length.
void check_model(const std::string& name, const TriMesh& skin, const TetMesh& tets, const TetrahedralizeReport& r,
                 bool has_bone, bool from_ct = false) {
  const TetQualityReport q = tet_quality(tets);
  std::printf("%s:\n%s%s", name.c_str(), r.summary().c_str(), q.summary().c_str());
  for (const std::string& note : r.notes) std::printf("note: %s\n", note.c_str());
  EXPECT_NEAR(r.tet_volume_mm3, r.skin_volume_mm3, 0.01 * r.skin_volume_mm3);
  if (has_bone) {
    ASSERT_GT(r.bone_volume_mm3, 0.0);
    EXPECT_NEAR(r.bone_tet_volume_mm3, r.bone_volume_mm3, 0.02 * r.bone_volume_mm3);
  }
  EXPECT_EQ(q.inverted_count, 0u);
  EXPECT_EQ(q.flat_count, 0u);
  const TriMesh boundary = tet_boundary_mesh(tets);
  if (from_ct) {
    EXPECT_EQ(check_topology(boundary).boundary_edge_count, 0u);
  } else {
    EXPECT_TRUE(check_topology(boundary).is_closed());
  }
  // The boundary follows the skin to well within the mesh's own edge length (measured as the mean boundary
  // edge, which is what a user sees).
  double edge_sum = 0.0;
  for (const Tri& t : boundary.triangles) edge_sum += (boundary.positions[t[0]] - boundary.positions[t[1]]).norm();
  const double mean_edge = edge_sum / static_cast<double>(boundary.triangle_count());
  const double to_skin = tet_test::one_way_distance(boundary, skin),
               from_skin = tet_test::one_way_distance(skin, boundary);
  std::printf("Hausdorff: boundary->skin %.3f mm, skin->boundary %.3f mm, mean boundary edge %.2f mm\n", to_skin,
              from_skin, mean_edge);
  const double bound = from_ct ? r.edge_length_mm : mean_edge;
  EXPECT_LT(to_skin, bound);
  EXPECT_LT(from_skin, bound);
}

}  // namespace

TEST(RealInputs, HandScanKeepsItsVolume) {
  FORENSIM_REQUIRE_DATA(path, "hand-mesh/hand_closed.obj");
  // Arbitrary units, about 0.94 tall (its SOURCE.md): 200 mm per unit gives a 190 mm hand.
  const TriMesh skin = import_mesh(path, {"auto", 200.0});
  TetrahedralizeOptions o;
  o.edge_length_mm = 11.0;
  TetrahedralizeReport r;
  const TetMesh tets = tetrahedralize(skin, {}, o, &r);
  check_model("hand scan", skin, tets, r, false);
  EXPECT_GT(tets.vertex_count(), 4000u);
}

TEST(RealInputs, OpenBustIsClosedOnRequest) {
  FORENSIM_REQUIRE_DATA(path, "head-busts/demosthenes-low-res.obj");
  // Arbitrary units, 2.7 tall: 100 mm per unit gives a life-size bust. Its base is open (67 boundary edges).
  const TriMesh bust = import_mesh(path, {"auto", 100.0});
  ASSERT_FALSE(check_topology(bust).is_closed());
  // A statue's carved detail is far finer than a body's: at 0.12 mm from the surface Mesh_3 refines without
  // bound (16 GB), at 1 mm the bust meshes in 2 s.
  TetrahedralizeOptions o;
  o.edge_length_mm = 20.0;
  o.surface_distance_fraction = 0.05;
  // By default the base, a cut rather than a scan hole, is refused with a message that says what to do.
  try {
    tetrahedralize(bust, {}, o);
    FAIL() << "an open base was meshed without close_openings";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("close_openings"), std::string::npos) << e.what();
  }
  o.close_openings = true;
  TetrahedralizeReport r;
  const TetMesh tets = tetrahedralize(bust, {}, o, &r);
  std::printf("bust:\n%s", r.summary().c_str());
  ASSERT_FALSE(r.notes.empty()) << "the repair must be reported";
  EXPECT_NE(r.notes[0].find("repaired"), std::string::npos) << r.notes[0];
  EXPECT_GT(tets.tet_count(), 1000u);
  EXPECT_EQ(tet_quality(tets).inverted_count, 0u);
  EXPECT_TRUE(check_topology(tet_boundary_mesh(tets)).is_closed());
  EXPECT_NEAR(r.tet_volume_mm3, r.skin_volume_mm3, 0.01 * r.skin_volume_mm3);
}

TEST(RealInputs, CtHeadWithTheSkullAsBone) {
  FORENSIM_REQUIRE_DATA(path, "ct-head-headsq/quarter.nhdr");
  const ScalarGrid grid = read_volume(path);
  const TriMesh skin = ct_body_surfaces(grid, 500.0, 1150.0).skin;
  TetrahedralizeOptions o;
  o.target_nodes = 20000;
  TetrahedralizeReport r;
  const TetMesh tets = tetrahedralize_ct(grid, 500.0, 1150.0, o, &r);
  check_model("CT head (headsq)", skin, tets, r, true, true);
  EXPECT_GT(r.bone_tet_count, 1000u);
}
