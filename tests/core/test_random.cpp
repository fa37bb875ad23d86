#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/parallel.hpp"
#include "core/random.hpp"

using namespace forensim;

TEST(Random, StreamsAreReproducibleAndIndependent) {
  RandomStream a(42, 7), b(42, 7), c(42, 8), d(43, 7);
  for (int i = 0; i < 100; ++i) {
    const auto va = a.next_u64();
    EXPECT_EQ(va, b.next_u64());
    EXPECT_NE(va, c.next_u64());
    EXPECT_NE(va, d.next_u64());
  }
}

TEST(Random, UniformMomentsAndRange) {
  RandomStream s(1, 0);
  double sum = 0, sum2 = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double u = s.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n - 0.25, 1.0 / 12.0, 0.002);
}

TEST(Random, NormalMoments) {
  RandomStream s(3, 1);
  double sum = 0, sum2 = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = s.normal(2.0, 3.0);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 2.0, 0.03);
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), 3.0, 0.03);
}

TEST(Random, UniformIntCoversRangeInclusive) {
  RandomStream s(5, 5);
  std::vector<int> hits(7, 0);
  for (int i = 0; i < 7000; ++i) {
    const auto v = s.uniform_int(-3, 3);
    ASSERT_GE(v, -3);
    ASSERT_LE(v, 3);
    ++hits[static_cast<std::size_t>(v + 3)];
  }
  for (int h : hits) EXPECT_GT(h, 800);
}

TEST(Parallel, SumIsIdenticalAtAnyThreadCount) {
  auto f = [](std::size_t i) { return std::sin(static_cast<double>(i)) * 1e-3 + 1.0 / (1.0 + i); };
  set_thread_count(1);
  const double one = parallel_sum(0, 1000003, f, 1000);
  set_thread_count(2);
  const double two = parallel_sum(0, 1000003, f, 1000);
  set_thread_count(0);
  const double all = parallel_sum(0, 1000003, f, 1000);
  EXPECT_EQ(one, two);
  EXPECT_EQ(one, all);
}

TEST(Parallel, ForVisitsEveryIndexOnce) {
  std::vector<int> visits(10007, 0);
  parallel_for(
      0, visits.size(), [&](std::size_t i) { visits[i] += 1; }, 17);
  for (int v : visits) ASSERT_EQ(v, 1);
}

TEST(Parallel, InvokeRunsBothAndRethrows) {
  for (int threads : {1, 2}) {
    set_thread_count(threads);
    int a = 0, b = 0;
    parallel_invoke([&] { a = 1; }, [&] { b = 2; });
    EXPECT_EQ(a + b, 3) << threads << " threads";
    EXPECT_THROW(parallel_invoke([] {}, [] { throw std::runtime_error("second"); }), std::runtime_error);
  }
  set_thread_count(0);
}

// A branch that throws must not cancel the loops of the other branch: with TBB's bound contexts the sibling's
// nested loop returned early with iterations skipped and the sibling went on with half-filled data.
TEST(Parallel, ThrowingBranchLeavesTheSiblingsLoopsWhole) {
  for (int threads : {1, 2, 4}) {
    set_thread_count(threads);
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<int> visits(200000, 0);
      double sum = 0.0;
      const auto throws = [] { throw std::runtime_error("reader failed"); };
      const auto sibling = [&] {
        parallel_for(
            0, visits.size(), [&](std::size_t i) { visits[i] += 1; }, 64);
        sum = parallel_sum(
            0, 100000, [](std::size_t) { return 1.0; }, 100);
      };
      // The failing branch in either position; its exception comes out, the sibling's work is complete.
      EXPECT_THROW(parallel_invoke(throws, sibling), std::runtime_error);
      EXPECT_EQ(std::count(visits.begin(), visits.end(), 1), static_cast<long>(visits.size())) << threads;
      EXPECT_EQ(sum, 100000.0) << threads;
      std::fill(visits.begin(), visits.end(), 0);
      sum = 0.0;
      EXPECT_THROW(parallel_invoke(sibling, throws), std::runtime_error);
      EXPECT_EQ(std::count(visits.begin(), visits.end(), 1), static_cast<long>(visits.size())) << threads;
      EXPECT_EQ(sum, 100000.0) << threads;
    }
  }
  set_thread_count(0);
}

TEST(Parallel, InvokeRethrowsTheFirstBranchsErrorWhenBothThrow) {
  set_thread_count(2);
  for (int trial = 0; trial < 20; ++trial) {
    try {
      parallel_invoke([] { throw std::runtime_error("first"); }, [] { throw std::logic_error("second"); });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "first");
    }
  }
  set_thread_count(0);
}
