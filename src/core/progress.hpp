#pragma once
/// Progress reporting for long runs: a bar with percentage and ETA when stderr is a terminal, plain
/// "label: 40% (12/30) eta 1m05s" lines at most every few seconds otherwise. Thread-safe advance().
/// Also the interruption flag that long runs poll to stop cleanly at a checkpoint.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace forensim {

/// How progress is shown.
enum class ProgressStyle { automatic, bar, lines, quiet };

/// Sets the process-wide progress style (automatic = bar on a TTY, lines otherwise).
void set_progress_style(ProgressStyle style);

class Progress {
 public:
  /// `label` names the task; `total` is the number of work units (steps, frames, texels).
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Marks `units` more work units done (thread-safe).
  void advance(std::size_t units = 1);
  /// Sets the number of units done (for resumed runs).
  void set_done(std::size_t done);
  /// Prints the final line; called by the destructor if not called before.
  void finish();
  std::size_t done() const { return m_done.load(); }

 private:
  void draw(bool final_line);
  std::string m_label;
  std::size_t m_total;
  std::atomic<std::size_t> m_done{0};
  std::size_t m_start_done = 0;
  std::chrono::steady_clock::time_point m_start, m_last_draw;
  std::mutex m_mutex;
  bool m_finished = false;
  ProgressStyle m_style;
};

/// Formats a duration in seconds as "1h02m", "3m05s" or "4.2s".
std::string format_duration(double seconds);

/// Installs a SIGINT/SIGTERM handler that sets the interruption flag instead of killing the process
/// (a second signal exits at once).
void install_interrupt_handler();
/// True once the user asked to stop; long loops check it and write a checkpoint.
bool interrupt_requested();
/// Sets or clears the flag (tests use this to simulate an interruption).
void set_interrupt_requested(bool requested);

}  // namespace forensim
