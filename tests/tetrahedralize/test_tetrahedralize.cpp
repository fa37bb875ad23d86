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

// An L-shaped prism (the L's arms along +x and +y, 10 mm long and 4 mm wide, 4 mm high): not convex, so a
// segment between two points inside can leave it.
TriMesh l_prism() {
  const double xy[6][2] = {{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}};
  TriMesh m;
  for (double z : {0.0, 4.0})
    for (const auto& p : xy) m.positions.emplace_back(p[0], p[1], z);
  // The L's floor as triangles (0 1 2, 0 2 3, 0 3 4, 0 4 5 turn counter-clockwise seen from +z).
  const Tri top[4] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  for (const Tri& t : top) {
    m.triangles.push_back({t[0], t[2], t[1]});              // bottom faces -z
    m.triangles.push_back({t[0] + 6, t[1] + 6, t[2] + 6});  // top faces +z
  }
  for (Index i = 0; i < 6; ++i) {
    const Index j = (i + 1) % 6;
    m.triangles.push_back({i, j, j + 6});
    m.triangles.push_back({i, j + 6, i + 6});
  }
  return m;
}

// Mesh_3's polyhedral domain needs embedded patches: a skin through itself is repaired (its crossing triangles
// replaced, with a note) and the tets fill the union of its parts; a bone whose corners lie inside the skin but
// whose edges leave it is an InputError naming the bone, not a crash inside the mesher.
TEST(Tetrahedralize, CrossingSurfacesAreRepairedOrRefused) {
  TetrahedralizeOptions o;
  o.edge_length_mm = 5.0;
  // A sphere whose +x pole is pulled through the sphere and 5 mm out of its far side (a fold pressed through the
  // surface): one closed surface passing through itself near the -x pole. Its repair keeps about the ball.
  const double r = 20.0;
  TriMesh folded = make_icosphere(Vec3::Zero(), r, 3);
  folded.normals.clear();
  std::size_t pole = 0;
  for (std::size_t v = 0; v < folded.positions.size(); ++v)
    if (folded.positions[v].x() > folded.positions[pole].x()) pole = v;
  folded.positions[pole] = Vec3(-r - 5.0, 0.0, 0.0);
  TetrahedralizeReport report;
  const TetMesh m = tetrahedralize(folded, {}, o, &report);
  const double ball = 4.0 / 3.0 * M_PI * r * r * r;
  EXPECT_NEAR(tet_mesh_volume(m), ball, 0.05 * ball);
  ASSERT_FALSE(report.notes.empty());
  EXPECT_NE(report.notes[0].find("skin surface passed through itself"), std::string::npos) << report.notes[0];
  // A tetrahedral bone with every corner inside the L but one edge across its notch.
  const TriMesh l = l_prism();
  ASSERT_GT(enclosed_volume(l), 0.0);
  TriMesh bone;
  bone.positions = {Vec3(8, 1, 1), Vec3(1, 8, 1), Vec3(1, 1, 1), Vec3(1, 1, 3)};
  bone.triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  o.edge_length_mm = 1.0;
  try {
    tetrahedralize(l, {bone}, o);
    ADD_FAILURE() << "bone crossing the skin accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "bone surface 0");
    EXPECT_NE(std::string(e.what()).find("the skin surface's triangles"), std::string::npos) << e.what();
  }
}

// A refinement that has not finished within time_limit_s ends with an InputError saying so.
TEST(Tetrahedralize, RefinementPastItsTimeBoundIsAnInputError) {
  const TriMesh skin = make_icosphere(Vec3::Zero(), 20.0, 4);
  TetrahedralizeOptions o;
  o.edge_length_mm = 0.4;  // about a million nodes: minutes of refinement
  o.time_limit_s = 0.2;
  try {
    tetrahedralize(skin, {}, o);
    ADD_FAILURE() << "time bound not applied";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did not finish within its bound"), std::string::npos) << e.what();
  }
  o.time_limit_s = -1.0;
  EXPECT_THROW(tetrahedralize(skin, {}, o), InputError);
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
