#include "craniofacial/skull_registration.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "synthetic_skull.hpp"

using namespace forensim;
using namespace forensim::test;

namespace {

double rotation_angle(const Mat3& a, const Mat3& b) {
  return Eigen::AngleAxisd(a * b.transpose()).angle();
}

}  // namespace

TEST(SkullRegistration, RecoversAKnownSimilarity) {
  const TriMesh reference = skull_mesh(5);
  const Similarity truth = known_similarity();
  const TriMesh target = moved(reference, truth, false);
  double rms = -1.0;
  const Similarity s = register_similarity(reference, target, {}, &rms);
  EXPECT_NEAR(s.scale, truth.scale, 1e-5);
  EXPECT_LT(rotation_angle(s.rotation, truth.rotation), 1e-5);
  EXPECT_LT((s.translation - truth.translation).norm(), 1e-3);
  EXPECT_LT(rms, 1e-3);
}

TEST(SkullRegistration, PrincipalAxisStartsRecoverAHalfTurn) {
  // Turned by 160 degrees the meshes' own orientation alone is a wrong start for one-way pairs (quarter turns
  // off); a principal-axis start is not.
  const TriMesh reference = skull_mesh(5);
  Similarity truth;
  truth.scale = 0.9;
  truth.rotation = Mat3(Eigen::AngleAxisd(160.0 * M_PI / 180.0, Vec3(0.1, 0.3, 1.0).normalized()));
  truth.translation = Vec3(-5.0, 12.0, 3.0);
  const TriMesh target = moved(reference, truth, false);
  const Similarity s = register_similarity(reference, target);
  EXPECT_NEAR(s.scale, truth.scale, 1e-5);
  EXPECT_LT(rotation_angle(s.rotation, truth.rotation), 1e-5);
  SimilarityRegistrationOptions own_orientation_only;
  own_orientation_only.principal_axis_starts = false;
  own_orientation_only.quarter_turn_starts = false;
  own_orientation_only.reverse_weight = 0.0;  // one way: the two-way pairs widen the basin enough to find it
  const Similarity wrong = register_similarity(reference, target, own_orientation_only);
  EXPECT_GT(rotation_angle(wrong.rotation, truth.rotation), 0.1);
}

TEST(SkullRegistration, NonRigidStageFollowsASmoothDeformation) {
  const TriMesh reference = skull_mesh(5);
  const Similarity truth = known_similarity();
  const TriMesh target = moved(reference, truth, true);
  const SkullRegistration reg = register_skull(reference, target);
  EXPECT_LT(reg.rms_mm, 0.5 * reg.similarity_rms_mm);
  EXPECT_LT(reg.rms_mm, 0.3);
  double sum = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < reference.positions.size(); ++i) {
    const double e = (reg.map(reference.positions[i]) - target.positions[i]).norm();
    sum += e;
    worst = std::max(worst, e);
  }
  const double mean = sum / static_cast<double>(reference.positions.size());
  std::printf("scale %.5f vs %.5f, angle %.5f, translation %.3f %.3f %.3f vs %.3f %.3f %.3f\n", reg.similarity.scale,
              truth.scale, rotation_angle(reg.similarity.rotation, truth.rotation), reg.similarity.translation.x(),
              reg.similarity.translation.y(), reg.similarity.translation.z(), truth.translation.x(),
              truth.translation.y(), truth.translation.z());
  EXPECT_LT(mean, 1.0);
  EXPECT_LT(worst, 3.0);
  std::printf("similarity rms %.3f mm, non-rigid rms %.3f mm, vertex error mean %.3f max %.3f mm\n",
              reg.similarity_rms_mm, reg.rms_mm, mean, worst);
  // Without the non-rigid stage the map is the similarity alone.
  SkullRegistrationOptions rigid;
  rigid.non_rigid_enabled = false;
  const SkullRegistration sim = register_skull(reference, target, rigid);
  EXPECT_EQ(sim.rms_mm, sim.similarity_rms_mm);
  EXPECT_LT((sim.map(reference.positions[7]) - sim.similarity.apply(reference.positions[7])).norm(), 1e-12);
  // The local residual is small near a well-fitted point and falls back to the global one far away.
  EXPECT_EQ(reg.local_residual_mm(Vec3(1e6, 0, 0), 5.0), reg.rms_mm);
}

TEST(SkullRegistration, SameResultAtAnyThreadCount) {
  const TriMesh reference = skull_mesh(3);
  const TriMesh target = moved(reference, known_similarity(), true);
  set_thread_count(1);
  const SkullRegistration one = register_skull(reference, target);
  set_thread_count(4);
  const SkullRegistration four = register_skull(reference, target);
  set_thread_count(0);
  EXPECT_EQ(one.similarity.scale, four.similarity.scale);
  EXPECT_EQ(one.similarity.rotation, four.similarity.rotation);
  EXPECT_EQ(one.similarity.translation, four.similarity.translation);
  ASSERT_EQ(one.node_weights.size(), four.node_weights.size());
  for (std::size_t j = 0; j < one.node_weights.size(); ++j) EXPECT_EQ(one.node_weights[j], four.node_weights[j]);
  EXPECT_EQ(one.rms_mm, four.rms_mm);
}

TEST(SkullRegistration, BadInputIsRejected) {
  const TriMesh reference = skull_mesh(3);
  EXPECT_THROW(register_skull(reference, TriMesh{}), InputError);
  EXPECT_THROW(register_skull(TriMesh{}, reference), InputError);
  TriMesh flat = reference;
  for (Vec3& p : flat.positions) p = Vec3(1, 2, 3);
  EXPECT_THROW(register_skull(reference, flat), InputError);
  SkullRegistrationOptions bad;
  bad.non_rigid.stiffness_schedule.clear();
  EXPECT_THROW(register_skull(reference, reference, bad), InputError);
  bad = {};
  bad.similarity.trim_fraction = 0.95;
  EXPECT_THROW(register_skull(reference, reference, bad), InputError);
  bad = {};
  bad.non_rigid.node_count = 2;
  EXPECT_THROW(register_skull(reference, reference, bad), InputError);
  bad = {};
  bad.non_rigid.reverse_weight = -1.0;
  EXPECT_THROW(register_skull(reference, reference, bad), InputError);
  bad = {};
  bad.non_rigid.reverse_trim_fraction = 0.9;
  EXPECT_THROW(register_skull(reference, reference, bad), InputError);
}

TEST(SkullRegistration, BasinsAreTheFirstOfEachGroupOfNearbyRotations) {
  const auto turn = [](double degrees, const Vec3& axis) {
    return Mat3(Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()));
  };
  EXPECT_NEAR(rotation_angle_deg(turn(10.0, Vec3::UnitX()), turn(44.0, Vec3::UnitX())), 34.0, 1e-9);
  EXPECT_NEAR(rotation_angle_deg(Mat3::Identity(), turn(180.0, Vec3(1, 2, 3))), 180.0, 1e-6);
  EXPECT_NEAR(rotation_angle_deg(turn(70.0, Vec3(0, 1, 1)), turn(70.0, Vec3(0, 1, 1))), 0.0, 1e-6);
  // Ranked best first: a pose, a near copy of it (4 degrees off), the same skull pitched 34 degrees, a copy of that,
  // and a half turn.
  std::vector<Similarity> ranked(5);
  ranked[1].rotation = turn(4.0, Vec3::UnitX());
  ranked[2].rotation = turn(34.0, Vec3::UnitX());
  ranked[3].rotation = turn(36.0, Vec3::UnitX()) * turn(3.0, Vec3::UnitZ());
  ranked[4].rotation = turn(180.0, Vec3::UnitZ());
  for (Similarity& s : ranked) s.translation = Vec3(1, 2, 3);
  EXPECT_EQ(distinct_basins(ranked, 10.0, 10), (std::vector<std::size_t>{0, 2, 4}));
  EXPECT_EQ(distinct_basins(ranked, 10.0, 2), (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(distinct_basins(ranked, 0.0, 10).size(), 5u);    // every rotation its own basin
  EXPECT_EQ(distinct_basins(ranked, 179.0, 10).size(), 2u);  // only the half turn lies further
  EXPECT_TRUE(distinct_basins({}, 10.0, 3).empty());
  EXPECT_THROW(distinct_basins(ranked, -1.0, 3), InputError);
}
