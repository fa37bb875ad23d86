#include <gtest/gtest.h>

#include "core/job.hpp"

using namespace forensim;

TEST(Job, ReadsValuesAndDefaults) {
  JobDocument doc = JobDocument::parse(R"({"days": 30, "environment": {"humidity": 0.2}})", "job.json");
  JobNode root = doc.root();
  EXPECT_EQ(root.get<int>("days", 10), 30);
  EXPECT_DOUBLE_EQ(root.child("environment").get_number("humidity", 0.5, 0, 1), 0.2);
  EXPECT_DOUBLE_EQ(root.child("environment").get_number("temperature_c", 25.0, -50, 80), 25.0);
  EXPECT_NO_THROW(doc.check_all_used());
  EXPECT_EQ(doc.resolved()["environment"]["temperature_c"], 25.0);
  EXPECT_EQ(doc.resolved()["days"], 30);
}

TEST(Job, UnknownKeyIsReportedWithPathAndSuggestion) {
  JobDocument doc = JobDocument::parse(R"({"environment": {"humdity": 0.2}})", "job.json");
  (void)doc.root().child("environment").get_number("humidity", 0.5, 0, 1);
  try {
    doc.check_all_used();
    FAIL() << "expected a JobError";
  } catch (const JobError& e) {
    EXPECT_EQ(e.key_path(), "/environment/humdity");
    EXPECT_NE(std::string(e.what()).find("did you mean 'humidity'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("job.json"), std::string::npos);
  }
}

TEST(Job, UnknownTopLevelKeyInArrayItem) {
  JobDocument doc = JobDocument::parse(R"({"strokes": [{"radius_mm": 2, "colour": 1}]})", "j");
  for (const auto& s : doc.root().children("strokes")) (void)s.get<double>("radius_mm", 1.0);
  EXPECT_THROW(doc.check_all_used(), JobError);
}

TEST(Job, SyntaxErrorNamesLineAndColumn) {
  try {
    JobDocument::parse("{\n  \"a\": 1,\n  \"b\": ]\n}", "bad.json");
    FAIL();
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
}

TEST(Job, WrongTypeAndRangeAreErrors) {
  JobDocument doc = JobDocument::parse(R"({"days": "ten", "seed": -1, "mode": "fast"})", "j");
  EXPECT_THROW((void)doc.root().get<double>("days", 1.0), JobError);
  EXPECT_THROW((void)doc.root().get_integer("seed", 0, 0, 100), JobError);
  EXPECT_THROW((void)doc.root().get_choice("mode", "slow", {"slow", "exact"}), JobError);
  EXPECT_THROW((void)doc.root().require<int>("missing"), JobError);
}

TEST(Job, NumberBeyondDoubleRangeIsAJobError) {
  // nlohmann::json reports it as out_of_range, which JobDocument::parse once let escape (found by fuzz/job).
  try {
    JobDocument::parse(R"({"days": 1e999})", "big.json");
    FAIL();
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find("1e999"), std::string::npos) << e.what();
  }
}

TEST(Job, NonObjectRootIsRejected) {
  EXPECT_THROW(JobDocument::parse("[1,2]", "j"), JobError);
}

TEST(Job, EditDistance) {
  EXPECT_EQ(edit_distance("humidity", "humdity"), 1u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("same", "same"), 0u);
}
