// Registry and timing helpers of `forensim bench`.

#include "bench_registry.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>

namespace forensim::cli {

std::vector<BenchTarget>& bench_registry() {
  static std::vector<BenchTarget> targets;
  return targets;
}

RegisterBench::RegisterBench(BenchTarget target) {
  bench_registry().push_back(std::move(target));
}

BenchTiming time_repeated(int repetitions, const std::function<void()>& fn) {
  std::vector<double> seconds;
  const int n = std::max(repetitions, 1);
  seconds.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    seconds.push_back(seconds_since(start));
  }
  return summarise_samples(std::move(seconds));
}

BenchTiming summarise_samples(std::vector<double> samples) {
  std::sort(samples.begin(), samples.end());
  const std::size_t m = samples.size();
  return {m % 2 == 1 ? samples[m / 2] : 0.5 * (samples[m / 2 - 1] + samples[m / 2]), samples.front()};
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format_mib(std::size_t bytes) {
  return std::to_string(bytes / (1024 * 1024)) + " MiB";
}

std::size_t peak_rss_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

}  // namespace forensim::cli
