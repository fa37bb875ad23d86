#include <gtest/gtest.h>

#include <CGAL/Random.h>

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
#include "tetrahedralize/tet_quality.hpp"
#include "tetrahedralize/tetrahedralize.hpp"

using namespace forensim;

#include "tet_model_tests.hpp"

INSTANTIATE_TEST_SUITE_P(Quick, ModelTets, ::testing::Values("spheres"));

TEST(Tetrahedralize, InwardSkinIsFlipped) {
  TriMesh skin = make_icosphere(Vec3::Zero(), 20.0, 2);
  for (Tri& t : skin.triangles) std::swap(t[1], t[2]);
  TetrahedralizeOptions o;
  o.edge_length_mm = 8.0;
  TetrahedralizeReport r;
  const TetMesh m = tetrahedralize(skin, {}, o, &r);
  EXPECT_NEAR(tet_mesh_volume(m), -enclosed_volume(skin), 0.03 * -enclosed_volume(skin));
  EXPECT_FALSE(r.notes.empty());
}

TEST(Tetrahedralize, SmallHoleIsRepaired) {
  TriMesh skin = make_icosphere(Vec3::Zero(), 20.0, 3);
  skin.triangles.erase(skin.triangles.begin());
  TetrahedralizeOptions o;
  o.edge_length_mm = 8.0;
  TetrahedralizeReport r;
  const TetMesh m = tetrahedralize(skin, {}, o, &r);
  EXPECT_GT(m.tet_count(), 0u);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes[0].find("repaired"), std::string::npos);
}

TEST(Tetrahedralize, BadInputsAreInputErrors) {
  const TriMesh skin = make_icosphere(Vec3::Zero(), 20.0, 3);
  TetrahedralizeOptions o;
  o.edge_length_mm = 8.0;
  // Empty skin.
  EXPECT_THROW(tetrahedralize(TriMesh{}, {}, o), InputError);
  // A hemisphere: one hole too big for repair.
  TriMesh open = skin;
  std::vector<bool> keep(open.triangle_count());
  for (std::size_t t = 0; t < keep.size(); ++t) keep[t] = open.positions[open.triangles[t][0]].z() > -5.0;
  open = extract_triangles(open, keep);
  try {
    tetrahedralize(open, {}, o);
    ADD_FAILURE() << "open skin accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "skin surface");
  }
  // A bone partly outside the skin.
  try {
    tetrahedralize(skin, {make_icosphere(Vec3(18, 0, 0), 5.0, 2)}, o);
    ADD_FAILURE() << "bone outside the skin accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "bone surface 0");
  }
  // Overlapping bones.
  EXPECT_THROW(tetrahedralize(skin, {make_icosphere(Vec3(2, 0, 0), 5.0, 2), make_icosphere(Vec3(-2, 0, 0), 5.0, 2)}, o),
               InputError);
  // An empty bone.
  EXPECT_THROW(tetrahedralize(skin, {TriMesh{}}, o), InputError);
  // No size.
  EXPECT_THROW(tetrahedralize(skin, {}, TetrahedralizeOptions{}), InputError);
  // Refinement past the node limit stops with an error instead of filling the memory.
  TetrahedralizeOptions fine = o;
  fine.edge_length_mm = 1.0;
  fine.max_nodes = 200;
  try {
    tetrahedralize(skin, {}, fine);
    ADD_FAILURE() << "runaway refinement not stopped";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("limit of 200 nodes"), std::string::npos) << e.what();
  }
  // An offset bone where the body is too thin for it.
  TetrahedralizeOptions offset = o;
  offset.bone_offset_mm = 30.0;
  EXPECT_THROW(tetrahedralize(skin, {}, offset), InputError);
  // Non-finite position.
  TriMesh nan = skin;
  nan.positions[0].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(tetrahedralize(nan, {}, o), InputError);
}

// Same input and seed, same tets, whatever ran before in the process: CGAL's process-wide default random
// generator (which parts of Mesh_3 and CGAL's other packages draw from) is advanced between the two runs.
TEST(Tetrahedralize, SameSeedSameTetsAfterOtherRandomDraws) {
  const TriMesh skin = make_icosphere(Vec3::Zero(), 20.0, 3);
  TetrahedralizeOptions o;
  o.edge_length_mm = 5.0;
  o.manifold_boundary = false;
  o.perturb = false;
  const TetMesh first = tetrahedralize(skin, {}, o);
  for (int i = 0; i < 1000; ++i) (void)CGAL::get_default_random().get_double();
  // A different heap: blocks of many sizes, every other one freed.
  std::vector<std::unique_ptr<char[]>> blocks;
  for (int i = 0; i < 20000; ++i) blocks.emplace_back(new char[std::size_t(16 + (i * 7919) % 600)]);
  for (std::size_t i = 0; i < blocks.size(); i += 2) blocks[i].reset();
  const TetMesh second = tetrahedralize(skin, {}, o);
  ASSERT_EQ(first.positions.size(), second.positions.size());
  ASSERT_EQ(first.tets.size(), second.tets.size());
  EXPECT_TRUE(first.positions == second.positions);
  EXPECT_TRUE(first.tets == second.tets);
}
