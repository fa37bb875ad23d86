// The template head carried onto a skull by its skull's registration (template_carry.hpp).
#include "craniofacial/template_carry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "template_head_fixture.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;

namespace {

Similarity turned_and_grown() {
  Similarity s;
  s.scale = 1.1;
  s.rotation = Eigen::AngleAxisd(0.35, Vec3(0.2, -0.3, 1.0).normalized()).toRotationMatrix();
  s.translation = Vec3(5.0, -3.0, 12.0);
  return s;
}

double max_gap(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

}  // namespace

TEST(CarryTemplate, ASimilarityMapsEveryPartAndScalesTheDepths) {
  const TemplateHead& head = coarse_template_head();
  SkullRegistration reg;
  reg.similarity = turned_and_grown();
  const TemplateHead carried = carry_template_head(head, reg);
  const auto mapped = [&](std::vector<Vec3> points) {
    for (Vec3& p : points) p = reg.similarity.apply(p);
    return points;
  };
  EXPECT_LT(max_gap(carried.skin.positions, mapped(head.skin.positions)), 1e-9);
  EXPECT_LT(max_gap(carried.skull.positions, mapped(head.skull.positions)), 1e-9);
  // Triangles, UVs and charts are the template's: the texture follows.
  EXPECT_EQ(carried.skin.triangles, head.skin.triangles);
  EXPECT_EQ(carried.skin.uvs, head.skin.uvs);
  EXPECT_EQ(carried.skin.triangle_uvs, head.skin.triangle_uvs);
  EXPECT_EQ(carried.triangle_chart, head.triangle_chart);
  // Normals turn with the rotation (a similarity keeps angles).
  ASSERT_EQ(carried.skin.normals.size(), head.skin.normals.size());
  double normal_gap = 0.0;
  for (std::size_t i = 0; i < head.skin.normals.size(); ++i) {
    normal_gap =
        std::max(normal_gap, (carried.skin.normals[i] - reg.similarity.rotation * head.skin.normals[i]).norm());
  }
  EXPECT_LT(normal_gap, 1e-9);
  ASSERT_EQ(carried.muscles.size(), head.muscles.size());
  for (std::size_t m = 0; m < head.muscles.size(); ++m) {
    EXPECT_LT(max_gap(carried.muscles[m].grid, mapped(head.muscles[m].grid)), 1e-9) << head.muscles[m].name;
  }
  ASSERT_EQ(carried.skin_landmarks.size(), head.skin_landmarks.size());
  for (std::size_t i = 0; i < head.skin_landmarks.size(); ++i) {
    EXPECT_LT((carried.skin_landmarks[i].position - reg.similarity.apply(head.skin_landmarks[i].position)).norm(),
              1e-9);
  }
  ASSERT_EQ(carried.landmarks.size(), head.landmarks.size());
  for (std::size_t i = 0; i < head.landmarks.size(); ++i) {
    const TemplateLandmarkPair& a = head.landmarks[i];
    const TemplateLandmarkPair& b = carried.landmarks[i];
    EXPECT_EQ(b.skin_name, a.skin_name);
    EXPECT_LT((b.skull - reg.similarity.apply(a.skull)).norm(), 1e-9) << a.skin_name;
    EXPECT_LT((b.skin - reg.similarity.apply(a.skin)).norm(), 1e-9) << a.skin_name;
    EXPECT_NEAR(b.depth_mm, 1.1 * a.depth_mm, 1e-9) << a.skin_name;
    EXPECT_LT((b.skull_normal - reg.similarity.rotation * a.skull_normal).norm(), 1e-9) << a.skin_name;
  }
  EXPECT_NE(carried.source.find("carried onto the skull"), std::string::npos);
}

TEST(CarryTemplate, FollowsTheRegistrationsDisplacementField) {
  const TemplateHead& head = coarse_template_head();
  SkullRegistration reg;
  reg.similarity = turned_and_grown();
  reg.kernel_width_mm = 15.0;
  // Two nodes in front of the face, pushing it forward and down by a few millimetres.
  reg.node_positions = {reg.similarity.apply(Vec3(0, -80, 0)), reg.similarity.apply(Vec3(30, -70, -30))};
  reg.node_weights = {Vec3(0, -4, -2), Vec3(3, -2, 0)};
  const TemplateHead carried = carry_template_head(head, reg);
  std::size_t moved = 0, similarity_only = 0;
  for (std::size_t i = 0; i < head.skin.positions.size(); ++i) {
    const Vec3 expected = reg.map(head.skin.positions[i]);
    ASSERT_LT((carried.skin.positions[i] - expected).norm(), 1e-12) << i;
    const Vec3 by_similarity = reg.similarity.apply(head.skin.positions[i]);
    if ((expected - by_similarity).norm() > 1.0) ++moved;
    // Far from both nodes (beyond 10 kernel widths) the field has vanished: the similarity alone.
    double nearest = std::numeric_limits<double>::infinity();
    for (const Vec3& c : reg.node_positions) nearest = std::min(nearest, (by_similarity - c).norm());
    if (nearest > 150.0) {
      EXPECT_LT((carried.skin.positions[i] - by_similarity).norm(), 1e-9);
      ++similarity_only;
    }
  }
  EXPECT_GT(moved, 10u);
  EXPECT_GT(similarity_only, 10u);
  // Each pair stays one segment: its direction is that of its mapped points, of unit length.
  for (const TemplateLandmarkPair& p : carried.landmarks) {
    EXPECT_NEAR(p.skull_normal.norm(), 1.0, 1e-12) << p.skin_name;
    EXPECT_LT((p.skull + p.depth_mm * p.skull_normal - p.skin).norm(), 1e-9) << p.skin_name;
  }
}

TEST(CarryTemplate, RefusesAHeadWithoutSkinAndANonFiniteMap) {
  const TemplateHead& head = coarse_template_head();
  TemplateHead no_skin = head;
  no_skin.skin.triangles.clear();
  EXPECT_THROW(carry_template_head(no_skin, SkullRegistration{}), InputError);
  SkullRegistration broken;
  broken.kernel_width_mm = 10.0;
  broken.node_positions = {Vec3(0, -80, 0)};
  broken.node_weights = {Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0)};
  try {
    carry_template_head(head, broken);
    FAIL() << "a NaN in the field was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
  }
}
