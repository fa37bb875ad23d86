// Livor mortis start state: blood settles at the lowest points along gravity, is conserved, leaves contact
// areas pale, follows the gravity direction, and does not depend on the thread count.

#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "skin/livor_mortis.hpp"

using namespace forensim;

namespace {

TriMesh sphere() {
  return make_icosphere(Vec3(0, 0, 0), 50.0, 4);
}

double area_weighted(const TriMesh& mesh, const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> area(mesh.vertex_count(), 0.0);
  for (const Tri& t : mesh.triangles)
    for (Index v : t) area[v] += triangle_area(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]) / 3;
  double sum = 0;
  for (std::size_t i = 0; i < area.size(); ++i) sum += area[i] * a[i] * (b.empty() ? 1.0 : b[i]);
  return sum;
}

}  // namespace

TEST(LivorMortis, BloodSettlesAtTheLowestPoints) {
  const TriMesh skin = sphere();
  const LivorState s = settle_livor(skin, {});
  // Fill never increases with height; the lowest vertex is full and the top one drained.
  std::vector<std::size_t> order(skin.vertex_count());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return skin.positions[a][2] < skin.positions[b][2]; });
  for (std::size_t k = 1; k < order.size(); ++k)
    ASSERT_LE(s.vertex_hemoglobin[order[k]], s.vertex_hemoglobin[order[k - 1]] + 1e-12);
  EXPECT_NEAR(s.vertex_hemoglobin[order.front()], 1.0, 1e-12);
  EXPECT_NEAR(s.vertex_hemoglobin[order.back()], LivorSettings{}.residual_fill, 1e-12);
  EXPECT_GT(s.blood_level_mm, s.height_min_mm);
  EXPECT_LT(s.blood_level_mm, s.height_max_mm);
  EXPECT_NEAR(s.height_max_mm - s.height_min_mm, 100.0, 1e-6);
  for (std::size_t i = 0; i < s.vertex_saturation.size(); ++i)
    EXPECT_DOUBLE_EQ(s.vertex_saturation[i], s.vertex_hemoglobin[i] * s.vertex_capacity[i]);
}

TEST(LivorMortis, ConservesTheBlood) {
  const TriMesh skin = sphere();
  LivorSettings settings;
  settings.blood_fill = 0.4;
  const std::vector<std::uint8_t> contact = contact_near_plane(skin, settings.gravity, 4.0);
  const LivorState s = settle_livor(skin, contact, settings);
  const std::vector<double> ones(skin.vertex_count(), 1.0);
  const double before = settings.blood_fill * area_weighted(skin, ones, {});
  EXPECT_NEAR(area_weighted(skin, s.vertex_hemoglobin, s.vertex_capacity), before, 1e-6 * before);
  EXPECT_NEAR(s.blood_volume, before, 1e-6 * before);
}

TEST(LivorMortis, ContactAreasStayPale) {
  const TriMesh skin = sphere();
  const LivorSettings settings;
  const std::vector<std::uint8_t> contact = contact_near_plane(skin, settings.gravity, 5.0);
  const LivorState s = settle_livor(skin, contact, settings);
  double contact_max = 0.0, ring_min = 1.0;
  int in_contact = 0;
  for (std::size_t i = 0; i < skin.vertex_count(); ++i) {
    const double z = skin.positions[i][2] + 50.0;
    if (contact[i]) {
      ++in_contact;
      EXPECT_LE(z, 5.0 + 1e-9);
      contact_max = std::max(contact_max, s.vertex_saturation[i]);
    } else if (z < 15.0) {
      ring_min = std::min(ring_min, s.vertex_saturation[i]);
    }
  }
  ASSERT_GT(in_contact, 3);
  EXPECT_LE(contact_max, settings.contact_capacity + 1e-12);
  EXPECT_GT(ring_min, 0.9);  // just above the contact area the blood has settled
  // The blood pressed out of the contact area raises the level.
  EXPECT_GT(s.blood_level_mm, settle_livor(skin, {}, settings).blood_level_mm);
}

TEST(LivorMortis, FollowsTheGravityDirection) {
  const TriMesh skin = sphere();
  LivorSettings settings;
  settings.gravity = Vec3(1, 0, 0);  // lying on its side: +x is down
  const LivorState s = settle_livor(skin, {}, settings);
  std::size_t lowest = 0, highest = 0;
  for (std::size_t i = 0; i < skin.vertex_count(); ++i) {
    if (skin.positions[i][0] > skin.positions[lowest][0]) lowest = i;
    if (skin.positions[i][0] < skin.positions[highest][0]) highest = i;
  }
  EXPECT_NEAR(s.vertex_hemoglobin[lowest], 1.0, 1e-12);
  EXPECT_NEAR(s.vertex_hemoglobin[highest], settings.residual_fill, 1e-12);
}

TEST(LivorMortis, FaceMaskAndCapacityInputs) {
  const TriMesh skin = sphere();
  std::vector<std::uint8_t> faces(skin.triangle_count(), 0);
  faces[0] = 1;
  const std::vector<std::uint8_t> mask = vertex_mask_from_faces(skin, faces);
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 3);
  std::vector<double> capacity(skin.vertex_count(), 0.5);
  const LivorState s = settle_livor(skin, mask, {}, capacity);
  for (std::size_t i = 0; i < skin.vertex_count(); ++i) {
    EXPECT_LE(s.vertex_saturation[i], 0.5 + 1e-12);
    if (mask[i]) {
      EXPECT_DOUBLE_EQ(s.vertex_capacity[i], 0.5 * LivorSettings{}.contact_capacity);
    }
  }
}

TEST(LivorMortis, SameResultAtAnyThreadCount) {
  const TriMesh skin = sphere();
  const std::vector<std::uint8_t> contact = contact_near_plane(skin, Vec3(0, 0, -1), 3.0);
  set_thread_count(1);
  const LivorState one = settle_livor(skin, contact);
  set_thread_count(2);
  const LivorState two = settle_livor(skin, contact);
  set_thread_count(0);
  EXPECT_EQ(one.blood_level_mm, two.blood_level_mm);
  EXPECT_EQ(one.vertex_hemoglobin, two.vertex_hemoglobin);
}

TEST(LivorMortis, RejectsBadInput) {
  const TriMesh skin = sphere();
  EXPECT_THROW(settle_livor(skin, std::vector<std::uint8_t>(3, 0)), InputError);
  EXPECT_THROW(settle_livor(skin, {}, {}, std::vector<double>(skin.vertex_count(), 2.0)), InputError);
  LivorSettings s;
  s.gravity = Vec3::Zero();
  EXPECT_THROW(settle_livor(skin, {}, s), InputError);
  s = {};
  s.blood_fill = 0.01;  // below the residual fill
  EXPECT_THROW(settle_livor(skin, {}, s), InputError);
  EXPECT_THROW(settle_livor(TriMesh{}, {}), InputError);
  EXPECT_THROW(contact_near_plane(skin, Vec3(0, 0, -1), -1.0), InputError);
}
