#include <gtest/gtest.h>

#include <csignal>
#include <string>

#include "core/crash_report.hpp"

using namespace forensim;

TEST(CrashActivity, NestsAndRestoresThePreviousActivity) {
  EXPECT_EQ(current_crash_activity(), "");
  {
    CrashActivity outer("demo");
    EXPECT_EQ(current_crash_activity(), "demo");
    {
      CrashActivity inner("demo stage 'template'");
      EXPECT_EQ(current_crash_activity(), "demo stage 'template'");
    }
    EXPECT_EQ(current_crash_activity(), "demo");
  }
  EXPECT_EQ(current_crash_activity(), "");
}

TEST(CrashActivity, LongTextsAreCut) {
  const std::string long_text(1000, 'x');
  CrashActivity activity(long_text);
  EXPECT_EQ(current_crash_activity(), std::string(255, 'x'));
}

// The handler itself (under AddressSanitizer it is not installed: the sanitizer reports fatal signals itself).
#if !defined(__SANITIZE_ADDRESS__)
namespace {

[[noreturn]] void crash_in(const char* activity, int sig) {
  install_crash_handler("forensim-test");
  CrashActivity outer("forensim demo");
  CrashActivity inner(activity);
  std::raise(sig);
  std::abort();
}

// Recursion the optimiser cannot turn into a loop: each frame keeps a buffer the next call reads. The
// limit is read through a volatile, so the compiler cannot prove the recursion endless, yet never reached.
volatile int recursion_limit = 1 << 30;

[[gnu::noinline]] int recurse(int depth) {
  volatile char frame[4096];
  frame[0] = static_cast<char>(depth);
  if (depth >= recursion_limit) return frame[0];
  return recurse(depth + 1) + frame[0];
}

}  // namespace

TEST(CrashReportDeathTest, NamesTheSignalTheActivityAndPrintsATrace) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  // The process still ends by the signal, as it would without the handler.
  EXPECT_EXIT(crash_in("demo stage 'template'", SIGSEGV), testing::KilledBySignal(SIGSEGV),
              "forensim-test: crashed: segmentation fault \\(SIGSEGV\\) while demo stage 'template', in forensim "
              "demo\\.\nThis is a bug in forensim.*trace:\n.+");
  EXPECT_EXIT(crash_in("reading", SIGFPE), testing::KilledBySignal(SIGFPE), "floating-point exception.*reading");
}

TEST(CrashReportDeathTest, ReportsAStackOverflowFromItsOwnStack) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        install_crash_handler("forensim-test");
        CrashActivity activity("recursing");
        (void)recurse(0);
      },
      testing::KilledBySignal(SIGSEGV), "crashed: segmentation fault \\(SIGSEGV\\) while recursing");
}
#endif
