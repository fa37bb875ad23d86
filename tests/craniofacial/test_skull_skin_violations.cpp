// Skull/skin violation counts on shapes with known answers.
#include "craniofacial/skull_skin_violations.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

namespace {

/// A skull sphere (radius 94 mm) with a bump along +x that reaches 104 mm: it pierces a 100 mm skin.
TriMesh bumped_skull() {
  TriMesh skull = make_icosphere(Vec3::Zero(), 94.0, 4);
  for (Vec3& p : skull.positions) {
    const double c = p.normalized().x();
    if (c > 0.9) p *= 1.0 + (104.0 / 94.0 - 1.0) * (c - 0.9) / 0.1;
  }
  return skull;
}

/// `skin` with its vertices pushed along their radius by a Gaussian of `height_mm` around `direction`.
TriMesh bulged(const TriMesh& skin, const Vec3& direction, double height_mm, double width) {
  TriMesh out = skin;
  for (Vec3& p : out.positions) {
    const double c = p.normalized().dot(direction.normalized());
    p *= 1.0 + height_mm / p.norm() * std::exp(-(1.0 - c) * (1.0 - c) / (width * width));
  }
  return out;
}

void expect_same(const SkullSkinViolations& a, const SkullSkinViolations& b) {
  EXPECT_EQ(a.skull_vertices_outside, b.skull_vertices_outside);
  EXPECT_EQ(a.skin_vertices_inside, b.skin_vertices_inside);
  EXPECT_EQ(a.skull_outside_skin, b.skull_outside_skin);
  EXPECT_EQ(a.skin_inside_skull, b.skin_inside_skull);
  EXPECT_EQ(a.max_skull_protrusion_mm, b.max_skull_protrusion_mm);
  EXPECT_EQ(a.max_skin_intrusion_mm, b.max_skin_intrusion_mm);
  EXPECT_EQ(a.skull_vertex_count, b.skull_vertex_count);
  EXPECT_EQ(a.skin_vertex_count, b.skin_vertex_count);
}

}  // namespace

TEST(SkullSkinViolationCounter, WarpedSkinsGiveTheBruteForceCounts) {
  const TriMesh skull = bumped_skull();
  const TriMesh skin = make_icosphere(Vec3::Zero(), 100.0, 4);
  SkullSkinViolationCounter counter(skull);
  const SkullSkinViolations first = counter.count(skin);
  expect_same(first, count_skull_skin_violations(skull, skin));
  ASSERT_GT(first.skull_outside_skin, 0u);
  ASSERT_GT(first.skin_inside_skull, 0u);
  EXPECT_LE(counter.last_evaluated(), skull.positions.size() + skin.positions.size());
  // Warps of growing height over the bump: the skin sweeps past the bump's vertices round by round; and one on
  // the far side, where nothing changes side.
  const Vec3 x(1, 0, 0);
  std::size_t previous = first.skull_outside_skin, changes = 0;
  for (const double height : {1.0, 2.5, 3.5, 5.0, 8.0}) {
    const TriMesh warped = bulged(skin, x, height, 0.15);
    const SkullSkinViolations fast = counter.count(warped);
    changes += fast.skull_outside_skin != previous ? 1 : 0;
    previous = fast.skull_outside_skin;
    SCOPED_TRACE(height);
    expect_same(fast, count_skull_skin_violations(skull, warped));
    // Only points near the moved skin are evaluated again.
    EXPECT_LT(counter.last_evaluated(), (skull.positions.size() + skin.positions.size()) / 2);
  }
  EXPECT_GE(changes, 3u);  // the skin swept past skull vertices
  EXPECT_EQ(counter.count(bulged(skin, x, 8.0, 0.15)).total(), 0u);
  const TriMesh far_side = bulged(bulged(skin, x, 8.0, 0.15), -x, 3.0, 0.3);
  expect_same(counter.count(far_side), count_skull_skin_violations(skull, far_side));
  // Back to the first skin (remembered), and a whole shift of the skin (a full count).
  expect_same(counter.count(skin), first);
  TriMesh shifted = skin;
  for (Vec3& p : shifted.positions) p += Vec3(-20, 3, 1);
  expect_same(counter.count(shifted), count_skull_skin_violations(skull, shifted));
}

TEST(SkullSkinViolationCounter, OpenMeshesAndNewTrianglesGiveTheBruteForceCounts) {
  // An open skull (a cap of triangles removed: its winding number is fractional near the hole) and a skin
  // with other triangles than the last one counted.
  TriMesh skull = bumped_skull();
  std::vector<Tri> kept;
  for (const Tri& t : skull.triangles) {
    if (skull.positions[static_cast<std::size_t>(t[0])].normalized().z() < 0.95) kept.push_back(t);
  }
  skull.triangles = kept;
  const TriMesh skin = make_icosphere(Vec3::Zero(), 100.0, 4);
  SkullSkinViolationCounter counter(skull);
  for (const double height : {0.0, 2.0, 4.0}) {
    const TriMesh warped = bulged(skin, Vec3(1, 0, 0.2), height, 0.2);
    SCOPED_TRACE(height);
    expect_same(counter.count(warped), count_skull_skin_violations(skull, warped));
  }
  // An open skin (a cap removed): every skull vertex evaluated.
  TriMesh open_skin = bulged(skin, Vec3(1, 0, 0), 2.0, 0.2);
  std::vector<Tri> skin_kept;
  for (const Tri& t : open_skin.triangles) {
    if (open_skin.positions[static_cast<std::size_t>(t[0])].normalized().y() < 0.97) skin_kept.push_back(t);
  }
  open_skin.triangles = skin_kept;
  expect_same(counter.count(open_skin), count_skull_skin_violations(skull, open_skin));
  const TriMesh other = make_icosphere(Vec3(2, 0, 0), 100.0, 3);
  expect_same(counter.count(other), count_skull_skin_violations(skull, other));
  EXPECT_THROW(counter.count(TriMesh{}), InputError);
  EXPECT_THROW(SkullSkinViolationCounter{TriMesh{}}, InputError);
}

TEST(SkullSkinViolationCounter, GroupsSkullVerticesFarFromTheSkin) {
  // A finely meshed skull (edges about 3 mm) 6 mm under most of the skin: a first count evaluates the winding
  // number once per group of vertices joined by edges that cannot cross the skin, and gets the brute-force sides.
  TriMesh skull = make_icosphere(Vec3::Zero(), 94.0, 5);
  for (Vec3& p : skull.positions) {
    const double c = p.normalized().x();
    if (c > 0.9) p *= 1.0 + (104.0 / 94.0 - 1.0) * (c - 0.9) / 0.1;
  }
  const TriMesh skin = make_icosphere(Vec3::Zero(), 100.0, 4);
  SkullSkinViolationCounter counter(skull);
  const SkullSkinViolations v = counter.count(skin);
  expect_same(v, count_skull_skin_violations(skull, skin));
  EXPECT_GT(v.skull_outside_skin, 0u);
  EXPECT_LT(counter.last_evaluated(), skull.positions.size() / 2 + skin.positions.size());
}
