// Job processes: progress lines of core/progress.hpp parsed back, exit codes and output captured, and a
// running process cancelled.

#include <gtest/gtest.h>

#include <chrono>

#include "core/progress.hpp"
#include "server/job_process.hpp"
#include "support/test_support.hpp"

using namespace forensim;

TEST(JobProcess, ParsesTheProgressLinesForensimPrints) {
  auto p = parse_progress_line("drying: 40% (12/30) eta 1m05s");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->label, "drying");
  EXPECT_EQ(p->done, 12u);
  EXPECT_EQ(p->total, 30u);
  p = parse_progress_line("key positions: started (5 steps)");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->label, "key positions");
  EXPECT_EQ(p->done, 0u);
  EXPECT_EQ(p->total, 5u);
  p = parse_progress_line("drying: 30/30 done in 5.2s");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->done, 30u);
  EXPECT_FALSE(parse_progress_line("wrote out/run (abrasion, 5 key positions)"));
  EXPECT_FALSE(parse_progress_line("drying: 40% (12/ 30) eta"));
  EXPECT_FALSE(parse_progress_line("x: 1% (99999999999999999999999/1) eta 1s"));
}

TEST(JobProcess, CapturesOutputAndExitCode) {
  JobProcess ok(FORENSIM_CLI_PATH, {"--version"}, test::scratch_dir("job_process_ok"));
  ASSERT_TRUE(ok.wait_for(30.0));
  const ProcessSnapshot s = ok.snapshot();
  EXPECT_EQ(s.state, ProcessState::succeeded);
  EXPECT_EQ(s.exit_code, 0);
  ASSERT_FALSE(s.last_lines.empty());
  EXPECT_NE(s.last_lines.back().find("forensim "), std::string::npos);

  JobProcess bad(FORENSIM_CLI_PATH, {"info", "/nonexistent/skull.obj"}, test::scratch_dir("job_process_bad"));
  ASSERT_TRUE(bad.wait_for(30.0));
  const ProcessSnapshot b = bad.snapshot();
  EXPECT_EQ(b.state, ProcessState::failed);
  EXPECT_EQ(b.exit_code, 5);
  EXPECT_NE(b.error.find("/nonexistent/skull.obj"), std::string::npos) << b.error;
}

TEST(JobProcess, MissingExecutableFails) {
  JobProcess none("/nonexistent/forensim", {"--version"}, test::scratch_dir("job_process_none"));
  ASSERT_TRUE(none.wait_for(30.0));
  EXPECT_EQ(none.snapshot().state, ProcessState::failed);
  EXPECT_EQ(none.snapshot().exit_code, 127);
}

TEST(JobProcess, CancelStopsARunningProcess) {
  // A long mummify run: SIGTERM, and SIGKILL after the grace period if it does not stop by itself.
  JobProcess p(FORENSIM_CLI_PATH, {"mummify", "--days", "3000", "--no-pictures", "-o", "run"},
               test::scratch_dir("job_process_cancel"));
  EXPECT_FALSE(p.wait_for(0.3));
  EXPECT_EQ(p.snapshot().state, ProcessState::running);
  const auto start = std::chrono::steady_clock::now();
  p.cancel(1.0);
  ASSERT_TRUE(p.wait_for(20.0));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  EXPECT_EQ(p.snapshot().state, ProcessState::cancelled);
  p.cancel();  // no effect once ended
  EXPECT_EQ(p.snapshot().state, ProcessState::cancelled);
}
