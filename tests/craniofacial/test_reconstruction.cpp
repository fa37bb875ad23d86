// The reconstruction as one object: an incremental update after one landmark moves (or the guides change)
// gives the same head as a fresh reconstruction with the moved landmark; the depth vectors have the table's
// lengths; sources and provenance follow the landmarks.
#include "craniofacial/reconstruction.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "craniofacial/template_landmark_detection.hpp"
#include "template_head_fixture.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;

namespace {

constexpr double head_mm = 250.0;

const TissueDepths& table_depths() {
  static const TissueDepths d = select_tissue_depths(built_in_tissue_depth_table("ttable_2023"));
  return d;
}

ReconstructionOptions quick_options() {
  ReconstructionOptions o;
  o.fit.count_violations = false;
  // Updates keep the pair set; a fresh fit would look for correction pairs anew (test_violation_correction.cpp
  // checks that updates keep the corrections' targets).
  o.fit.correction.rounds = 0;
  return o;
}

double max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

/// Largest distance between two reconstructions' heads: skin, muscle grids and shapes, skin landmarks.
double head_difference(const ReconstructionResult& a, const ReconstructionResult& b) {
  double worst = max_distance(a.skin.positions, b.skin.positions);
  EXPECT_EQ(a.muscle_layouts.size(), b.muscle_layouts.size());
  EXPECT_EQ(a.muscles.size(), b.muscles.size());
  for (std::size_t m = 0; m < std::min(a.muscle_layouts.size(), b.muscle_layouts.size()); ++m) {
    worst = std::max(worst, max_distance(a.muscle_layouts[m].grid, b.muscle_layouts[m].grid));
  }
  for (std::size_t m = 0; m < std::min(a.muscles.size(), b.muscles.size()); ++m) {
    worst = std::max(worst, max_distance(a.muscles[m].skin_points, b.muscles[m].skin_points));
    worst = std::max(worst, max_distance(a.muscles[m].fibre_points, b.muscles[m].fibre_points));
  }
  EXPECT_EQ(a.skin_landmarks.names(), b.skin_landmarks.names());
  worst = std::max(worst, max_distance(a.skin_landmarks.positions(), b.skin_landmarks.positions()));
  return worst;
}

/// `set` with landmark `name` at `position`, edited.
LandmarkSet with_moved(const LandmarkSet& set, const std::string& name, const Vec3& position) {
  LandmarkSet out = set;
  out.set({name, position, LandmarkSource::edited, 1.0});
  return out;
}

}  // namespace

TEST(Reconstruction, DepthVectorsHaveTheTablesLengthsAndTheLandmarksSources) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  const Reconstruction r(head, head.skull, landmarks, table_depths(), quick_options());
  const ReconstructionResult& result = r.result();
  ASSERT_FALSE(result.depth_vectors.vectors.empty());
  for (const DepthVector& v : result.depth_vectors.vectors) {
    EXPECT_NEAR((v.skin_mm - v.bone_mm).norm(), *table_depths().depth_mm(v.bone_landmark), 1e-9) << v.bone_landmark;
    EXPECT_EQ(v.source, LandmarkSource::detected);
    EXPECT_EQ(result.skin_landmarks.at(v.skin_landmark).position_mm, v.skin_mm);
  }
  EXPECT_EQ(r.fit().given_pair_count, result.depth_vectors.vectors.size() - result.not_on_template.size());
  EXPECT_GT(r.fit().targets.size(), r.fit().given_pair_count);  // interpolated pairs
  EXPECT_LT(r.fit().max_landmark_residual_mm, 1e-9 * head_mm);
  EXPECT_EQ(r.provenance()["landmarks"]["items"].size(), result.depth_vectors.vectors.size());
}

TEST(Reconstruction, MovingOneLandmarkEqualsAFreshReconstruction) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  // A chin landmark no interpolated point depends on (one warp target changes), one of the cranium frame (the
  // interpolated cap moves with it) and a mandible arc's end (the arcs' points move with it).
  for (const std::string name : {"pg", "v", "go_L"}) {
    Reconstruction r(head, head.skull, landmarks, table_depths(), quick_options());
    const Vec3 moved = landmarks.at(name).position_mm + Vec3(1.5, -3.0, 2.0);
    const std::size_t changed = r.move_landmark(name, moved);
    EXPECT_GE(changed, 1u) << name;
    const Reconstruction fresh(head, head.skull, with_moved(landmarks, name, moved), table_depths(), quick_options());
    EXPECT_LT(head_difference(r.result(), fresh.result()), 1e-9 * head_mm) << name;
    ASSERT_EQ(r.fit().targets.size(), fresh.fit().targets.size()) << name;
    EXPECT_LT(max_distance(r.fit().targets, fresh.fit().targets), 1e-9 * head_mm) << name;
    // The moved landmark is edited, on the skull, with the table's depth.
    EXPECT_EQ(r.result().skull_landmarks.at(name).source, LandmarkSource::edited);
    for (const DepthVector& v : r.result().depth_vectors.vectors) {
      if (v.bone_landmark != name) continue;
      EXPECT_EQ(v.source, LandmarkSource::edited);
      EXPECT_NEAR(v.depth_mm, *table_depths().depth_mm(name), 1e-12);
      EXPECT_GT((v.bone_mm - landmarks.at(name).position_mm).norm(), 1.0);
    }
    // Moving it back restores the first head.
    r.move_landmark(name, landmarks.at(name).position_mm);
    const Reconstruction first(head, head.skull, landmarks, table_depths(), quick_options());
    EXPECT_LT(head_difference(r.result(), first.result()), 1e-9 * head_mm) << name;
  }
}

TEST(Reconstruction, GuidesAreReappliedAfterAMoveAndCanBeChangedAlone) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  Reconstruction r(head, head.skull, landmarks, table_depths(), quick_options());
  const ReconstructionResult unguided = r.result();
  FaceGuides guides;
  guides.mouth_corner_left_mm = unguided.skin_landmarks.at("ch'_L").position_mm.x() + 3.0;
  guides.mouth_corner_right_mm = unguided.skin_landmarks.at("ch'_R").position_mm.x() - 3.0;
  r.set_guides(guides);
  EXPECT_EQ(r.result().guides_adjusted.size(), 2u);
  EXPECT_NEAR(r.result().skin_landmarks.at("ch'_L").position_mm.x(), *guides.mouth_corner_left_mm, 1e-9 * head_mm);
  EXPECT_GT(head_difference(r.result(), unguided), 1.0);
  // Move a landmark with the guides in place: as a fresh guided reconstruction.
  const Vec3 moved = landmarks.at("gn").position_mm + Vec3(0, -2.0, -1.0);
  r.move_landmark("gn", moved);
  ReconstructionOptions guided_options = quick_options();
  guided_options.guides = guides;
  const Reconstruction fresh(head, head.skull, with_moved(landmarks, "gn", moved), table_depths(), guided_options);
  EXPECT_LT(head_difference(r.result(), fresh.result()), 1e-9 * head_mm);
  // Taking the guides away again gives the unguided head with the moved landmark.
  r.set_guides(std::nullopt);
  const Reconstruction plain(head, head.skull, with_moved(landmarks, "gn", moved), table_depths(), quick_options());
  EXPECT_LT(head_difference(r.result(), plain.result()), 1e-9 * head_mm);
  EXPECT_TRUE(r.result().guides_adjusted.empty());
}

TEST(Reconstruction, ViolationsAreStaleAfterAMoveUntilRecounted) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  Reconstruction r(head, head.skull, landmarks, table_depths(), quick_options());
  EXPECT_FALSE(r.result().violations_current);  // not counted on request
  r.recount_violations();
  EXPECT_TRUE(r.result().violations_current);
  EXPECT_TRUE(r.violations_json()["current"].get<bool>());
  EXPECT_EQ(r.result().violations_interpolated.skin_vertex_count, head.skin.positions.size());
  EXPECT_EQ(r.result().violations_final.total(), r.result().violations_interpolated.total());  // no guides
  r.move_landmark("g", landmarks.at("g").position_mm + Vec3(0, 0, 3));
  EXPECT_FALSE(r.result().violations_current);
  EXPECT_FALSE(r.violations_json()["current"].get<bool>());
}

TEST(Reconstruction, RejectsBadLandmarks) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  // Two spellings of one landmark.
  LandmarkSet twice = landmarks;
  twice.add({"nasion", landmarks.at("n").position_mm, LandmarkSource::imported, 1.0});
  EXPECT_THROW(Reconstruction(head, head.skull, twice, table_depths(), quick_options()), InputError);
  Reconstruction r(head, head.skull, landmarks, table_depths(), quick_options());
  EXPECT_THROW(r.move_landmark("not a landmark", Vec3::Zero()), InputError);
  EXPECT_THROW(r.move_landmark("pg", Vec3(0, -1e4, 0)), InputError);  // far from the skull
  EXPECT_THROW(r.move_landmark("pg", Vec3(0, NAN, 0)), InputError);
}

TEST(Reconstruction, RemovingALandmarkThenAddingItBackGivesTheSameFace) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet landmarks = template_skull_landmarks(head);
  Reconstruction r(head, head.skull, landmarks, table_depths(), quick_options());
  const ReconstructionResult first = r.result();
  const std::size_t given = r.fit().given_pair_count;
  r.remove_landmark("pogonion");  // any spelling
  EXPECT_FALSE(r.result().skull_landmarks.contains("pg"));
  EXPECT_EQ(r.fit().given_pair_count, given - 1);
  for (const DepthVector& v : r.result().depth_vectors.vectors) EXPECT_NE(v.bone_landmark, "pg");
  EXPECT_GT(max_distance(r.result().skin.positions, first.skin.positions), 0.1);  // the chin lost its pair
  LandmarkSet without = landmarks;
  without.remove("pg");
  const Reconstruction fresh(head, head.skull, without, table_depths(), quick_options());
  EXPECT_LT(max_distance(r.result().skin.positions, fresh.result().skin.positions), 1e-9 * head_mm);
  // Added back where it was: the first face (the pair now comes last in the warp's order).
  r.move_landmark("pg", landmarks.at("pg").position_mm);
  EXPECT_EQ(r.fit().given_pair_count, given);
  EXPECT_LT(max_distance(r.result().skin.positions, first.skin.positions), 1e-6);
}

TEST(Reconstruction, RemovingAnAbsentLandmarkOrTooManyThrowsAndChangesNothing) {
  const TemplateHead& head = coarse_template_head();
  const LandmarkSet all = template_skull_landmarks(head);
  Reconstruction r(head, head.skull, all, table_depths(), quick_options());
  EXPECT_THROW(r.remove_landmark("not a landmark"), InputError);
  r.remove_landmark("g");
  EXPECT_THROW(r.remove_landmark("g"), InputError);  // already removed
  // Five landmarks around the head: one can go, the next would leave 3 pairs for eq. 1.
  LandmarkSet five("five");
  for (const std::string name : {"g", "pg", "zy_L", "zy_R", "v"}) five.add(all.at(name));
  ReconstructionOptions plain = quick_options();
  plain.fit.interpolated_landmarks = false;
  Reconstruction small(head, head.skull, five, table_depths(), plain);
  ASSERT_EQ(small.fit().given_pair_count, 5u);
  EXPECT_EQ(small.remove_landmark("v"), 4u);
  const std::vector<Vec3> skin = small.result().skin.positions;
  EXPECT_THROW(small.remove_landmark("g"), InputError);
  EXPECT_TRUE(small.result().skull_landmarks.contains("g"));
  EXPECT_EQ(small.fit().given_pair_count, 4u);
  EXPECT_EQ(max_distance(small.result().skin.positions, skin), 0.0);
}
