// The reconstruction job (src/reconstruct/reconstruct_job.*): its record in run.json reads back to the job that
// ran, and the CT bone edge follows bone_iso.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/job.hpp"
#include "reconstruct/reconstruct_job.hpp"

using namespace forensim;

TEST(ReconstructJobRecord, RunRecordHoldsTheFlagsAndReadsBackToTheSameJob) {
  // A job file that says "evaluate": false, run with --evaluate --measure-guides --no-interpolated and a few
  // options typed: run.json must record what ran.
  JobDocument file = JobDocument::parse(
      R"({"version": 1, "evaluate": false, "measure_guides": false, "table": "rhine_1983", "seed": 3})", "job.json");
  ReconstructJob job = read_reconstruct_job(file.root(), ReconstructJob{}, "");
  EXPECT_FALSE(job.evaluate);
  job.evaluate = true;
  job.measure_guides = true;
  job.interpolated_landmarks = false;
  job.carry_template = false;
  job.ct = "scan.nhdr";
  job.seed = 9;
  job.expressions = {"smile"};
  job.uncertainty_samples = 8;
  const nlohmann::json record = reconstruct_job_record(job, file.resolved());
  EXPECT_TRUE(record["evaluate"].get<bool>());
  EXPECT_TRUE(record["measure_guides"].get<bool>());
  EXPECT_FALSE(record["interpolated_landmarks"].get<bool>());
  EXPECT_FALSE(record["carry_template"].get<bool>());
  EXPECT_EQ(record["table"], "rhine_1983");
  EXPECT_EQ(record["seed"].get<int>(), 9);
  // The record is a valid job that reads back to the job that ran, every key used.
  JobDocument again = JobDocument::parse(record.dump(), "run.json job");
  const ReconstructJob back = read_reconstruct_job(again.root(), ReconstructJob{}, "");
  EXPECT_NO_THROW(again.check_all_used());
  EXPECT_TRUE(back.evaluate);
  EXPECT_TRUE(back.measure_guides);
  EXPECT_FALSE(back.interpolated_landmarks);
  EXPECT_FALSE(back.carry_template);
  EXPECT_EQ(back.ct, "scan.nhdr");
  EXPECT_EQ(back.table, "rhine_1983");
  EXPECT_EQ(back.seed, 9u);
  EXPECT_EQ(back.expressions, std::vector<std::string>{"smile"});
  EXPECT_EQ(back.uncertainty_samples, 8);
}

TEST(ReconstructJobRecord, BoneEdgeIsTheHalfMaximumUnlessABoneIsoIsGiven) {
  const auto job_of = [](const std::string& text) {
    JobDocument file = JobDocument::parse(text, "job.json");
    const ReconstructJob job = read_reconstruct_job(file.root(), ReconstructJob{}, "");
    file.check_all_used();
    return job;
  };
  EXPECT_EQ(bone_edge_of(job_of(R"({"version": 1})")), "half-maximum");
  EXPECT_EQ(bone_edge_of(job_of(R"({"version": 1, "bone_iso": 1300})")), "iso");
  EXPECT_EQ(bone_edge_of(job_of(R"({"version": 1, "bone_edge": "iso"})")), "iso");
  EXPECT_EQ(bone_edge_of(job_of(R"({"version": 1, "bone_edge": "half-maximum"})")), "half-maximum");
  EXPECT_THROW(job_of(R"({"version": 1, "bone_edge": "steepest"})"), JobError);
  // The skull is read as the edge says; both ways of fixing the surface at once are refused.
  EXPECT_TRUE(skull_input_options(job_of(R"({"version": 1})")).half_maximum_height);
  const SkullInputOptions at_iso = skull_input_options(job_of(R"({"version": 1, "bone_iso": 1300})"));
  EXPECT_FALSE(at_iso.half_maximum_height);
  EXPECT_EQ(at_iso.bone_iso_value, 1300.0);
  EXPECT_THROW(skull_input_options(job_of(R"({"version": 1, "bone_iso": 1300, "bone_edge": "half-maximum"})")),
               InputError);
  // The record names the edge that ran, so it reads back to the same run even if the default changes.
  const ReconstructJob with_iso = job_of(R"({"version": 1, "bone_iso": 1300})");
  const nlohmann::json record = reconstruct_job_record(with_iso, nlohmann::json::object());
  EXPECT_EQ(record["bone_edge"], "iso");
  EXPECT_EQ(bone_edge_of(job_of(record.dump())), "iso");
}
