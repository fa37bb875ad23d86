#pragma once
/// `forensim bench SYSTEM`: timed runs of a system's hot steps on paper-sized inputs, printed beside the
/// timings its paper reports, with the process's peak memory. Each system registers a BenchTarget from its
/// own bench_<system>.cpp in this folder (static registration, like the subcommands); the Google Benchmark
/// programs in bench/ measure the same kernels in finer detail.

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace forensim::cli {

struct BenchOptions {
  int repetitions = 5;         ///< timed runs per row (the median is reported)
  std::string size = "paper";  ///< input size preset where a system has them (small, paper, fine)
};

/// One measured step.
struct BenchRow {
  std::string name;       ///< what was timed, e.g. "arm paper: dehydration step"
  double median_s = 0.0;  ///< median wall time of the repetitions, s
  double min_s = 0.0;     ///< fastest repetition, s
  double paper_s = -1.0;  ///< the paper's time for the same step (< 0: none)
  std::string paper_ref;  ///< where the paper's figure comes from ("Table 2, i7 3.4 GHz")
  double goal_s = -1.0;   ///< the project's goal for it (< 0: none)
  std::string note;       ///< counts or iterations worth printing beside the time
};

struct BenchTarget {
  std::string name;         ///< the SYSTEM argument: desiccation, wound, mummify, reconstruct...
  std::string description;  ///< one line for --help
  std::function<std::vector<BenchRow>(const BenchOptions&)> run;
};

/// Every registered target, in registration order.
std::vector<BenchTarget>& bench_registry();

/// Adds a target at static-initialisation time.
struct RegisterBench {
  explicit RegisterBench(BenchTarget target);
};

/// Median and minimum wall time of `repetitions` calls of `fn` (after none of warm-up: callers warm up).
struct BenchTiming {
  double median_s = 0.0;
  double min_s = 0.0;
};
BenchTiming time_repeated(int repetitions, const std::function<void()>& fn);
/// Median and minimum of `samples` (seconds; not empty).
BenchTiming summarise_samples(std::vector<double> samples);
/// Seconds from `start` to now.
double seconds_since(std::chrono::steady_clock::time_point start);
/// "N MiB" for a byte count.
std::string format_mib(std::size_t bytes);

/// Peak resident set size of this process so far, bytes (getrusage; 0 where unknown).
std::size_t peak_rss_bytes();

}  // namespace forensim::cli
