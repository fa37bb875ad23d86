#pragma once
/// Wall-clock timing of named stages, recorded in every run folder and the demo report.

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace forensim {

class Stopwatch {
 public:
  Stopwatch() : m_start(std::chrono::steady_clock::now()) {}
  void restart() { m_start = std::chrono::steady_clock::now(); }
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count(); }
  /// Seconds since construction or the last lap()/restart(), then restarts.
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - m_start).count();
    m_start = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point m_start;
};

/// Ordered list of (stage name, seconds); adding a name twice accumulates.
class Timings {
 public:
  void add(const std::string& stage, double seconds);
  double get(const std::string& stage) const;
  double total() const;
  const std::vector<std::pair<std::string, double>>& stages() const { return m_stages; }

 private:
  std::vector<std::pair<std::string, double>> m_stages;
};

/// Adds the time between construction and destruction to `timings` under `stage`.
class ScopedTimer {
 public:
  ScopedTimer(Timings& timings, std::string stage) : m_timings(timings), m_stage(std::move(stage)) {}
  ~ScopedTimer() { m_timings.add(m_stage, m_watch.seconds()); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  Timings& m_timings;
  std::string m_stage;
  Stopwatch m_watch;
};

}  // namespace forensim
