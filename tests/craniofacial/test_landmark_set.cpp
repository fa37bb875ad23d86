#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "craniofacial/landmark_set.hpp"

using namespace forensim;

TEST(LandmarkSet, KeepsOrderAndLooksUpByName) {
  LandmarkSet set("skull");
  set.add({"n", Vec3(0, -90, 10), LandmarkSource::imported, 1.0});
  set.add({"zy_L", Vec3(65, -20, 0), LandmarkSource::detected, 0.7});
  set.add({"g", Vec3(0, -92, 25), LandmarkSource::edited, 1.0});
  EXPECT_EQ(set.size(), 3u);
  EXPECT_EQ(set.names(), (std::vector<std::string>{"n", "zy_L", "g"}));
  EXPECT_EQ(*set.index_of("g"), 2u);
  EXPECT_EQ(set.at("zy_L").source, LandmarkSource::detected);
  const auto picked = set.positions({"g", "n"});
  EXPECT_EQ(picked[0], Vec3(0, -92, 25));
  EXPECT_EQ(picked[1], Vec3(0, -90, 10));
  EXPECT_THROW(set.positions({"g", "pg"}), InputError);
  set.set({"n", Vec3(1, 2, 3), LandmarkSource::edited, 1.0});
  EXPECT_EQ(set.at("n").position_mm, Vec3(1, 2, 3));
  EXPECT_EQ(set.size(), 3u);
  EXPECT_TRUE(set.remove("zy_L"));
  EXPECT_FALSE(set.remove("zy_L"));
  EXPECT_EQ(set.names(), (std::vector<std::string>{"n", "g"}));
}

TEST(LandmarkSet, RejectsDuplicatesNonFinitePositionsAndBadConfidence) {
  LandmarkSet set("skull");
  set.add({"n", Vec3::Zero(), LandmarkSource::imported, 1.0});
  EXPECT_THROW(set.add({"n", Vec3::Ones(), LandmarkSource::imported, 1.0}), InputError);
  EXPECT_THROW(set.add({"", Vec3::Ones(), LandmarkSource::imported, 1.0}), InputError);
  EXPECT_THROW(set.add({"g", Vec3(std::nan(""), 0, 0), LandmarkSource::imported, 1.0}), InputError);
  EXPECT_THROW(set.add({"g", Vec3(0, std::numeric_limits<double>::infinity(), 0), LandmarkSource::imported, 1.0}),
               InputError);
  EXPECT_THROW(set.add({"g", Vec3::Zero(), LandmarkSource::detected, 1.5}), InputError);
  EXPECT_THROW(set.add({"g", Vec3::Zero(), LandmarkSource::detected, std::nan("")}), InputError);
  EXPECT_EQ(set.size(), 1u);
}

TEST(LandmarkSet, TransformMapsEveryPosition) {
  LandmarkSet set("s");
  set.add({"a", Vec3(1, 2, 3), LandmarkSource::imported, 1.0});
  set.add({"b", Vec3(-4, 0, 9), LandmarkSource::detected, 0.5});
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  t.rotate(Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()));
  t.pretranslate(Vec3(5, -6, 7));
  const LandmarkSet moved = set.transformed(t);
  for (std::size_t i = 0; i < set.size(); ++i) {
    EXPECT_LT((moved[i].position_mm - t * set[i].position_mm).norm(), 1e-12);
    EXPECT_EQ(moved[i].name, set[i].name);
    EXPECT_EQ(moved[i].confidence, set[i].confidence);
  }
  // Distances are preserved by a rigid map.
  EXPECT_NEAR((moved[0].position_mm - moved[1].position_mm).norm(), (set[0].position_mm - set[1].position_mm).norm(),
              1e-12);
}

TEST(LandmarkSet, SourceWordsRoundTrip) {
  for (LandmarkSource s : {LandmarkSource::detected, LandmarkSource::imported, LandmarkSource::edited}) {
    EXPECT_EQ(parse_landmark_source(to_string(s), "t", ""), s);
  }
  EXPECT_THROW(parse_landmark_source("guessed", "t", ""), InputError);
}
