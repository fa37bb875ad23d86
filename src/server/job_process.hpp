#pragma once
/// A background job as a child process: the forensim executable itself, run with the arguments a job kind
/// prepared (`forensim --progress lines wound ...`). A process per job gives each job its own cancellation
/// (SIGTERM: the CLI's interrupt handler stops a mummify run at a checkpoint; SIGKILL after a grace period
/// for steps that do not poll it), its own memory, and no shared process-wide state with the server.
/// Its output (stdout and stderr together) is read by a thread that keeps the last lines and the latest
/// progress line.

#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace forensim {

/// A progress line of core/progress.hpp's "lines" style: "drying: 40% (12/30) eta 1m05s",
/// "drying: started (30 steps)" or "drying: 30/30 done in 5.2s".
struct ProgressLine {
  std::string label;
  std::size_t done = 0;
  std::size_t total = 0;
};

/// Parses one output line; std::nullopt when it is not a progress line.
std::optional<ProgressLine> parse_progress_line(const std::string& line);

enum class ProcessState { running, succeeded, failed, cancelled };

/// What a job process is doing, copied out under its lock.
struct ProcessSnapshot {
  ProcessState state = ProcessState::running;
  int exit_code = -1;                    ///< valid once not running (128 + signal when killed by a signal)
  std::optional<ProgressLine> progress;  ///< latest progress line seen
  std::vector<std::string> last_lines;   ///< up to the last 40 lines of output
  std::string error;                     ///< the "forensim: error: ..." line, when it failed
  double seconds = 0.0;                  ///< since the start (until the end once finished)
};

class JobProcess {
 public:
  /// Starts `executable` with `arguments` (argv[1..]) in working folder `working_dir`. Throws IoError when
  /// the process cannot be started.
  JobProcess(const std::filesystem::path& executable, const std::vector<std::string>& arguments,
             const std::filesystem::path& working_dir);
  /// Cancels a running process and waits for it.
  ~JobProcess();
  JobProcess(const JobProcess&) = delete;
  JobProcess& operator=(const JobProcess&) = delete;

  ProcessSnapshot snapshot() const;
  /// Asks the process to stop (SIGTERM), and kills it (SIGKILL) if it has not ended after `grace_seconds`.
  /// Returns at once; the state becomes `cancelled` when it ends. No effect once finished.
  void cancel(double grace_seconds = 3.0);
  /// Waits until the process has ended or `seconds` have passed; true when it has ended.
  bool wait_for(double seconds) const;

 private:
  void read_output(int fd);
  pid_t m_pid = -1;
  mutable std::mutex m_mutex;
  mutable std::condition_variable m_ended;
  ProcessSnapshot m_snapshot;
  std::deque<std::string> m_lines;
  bool m_cancel_requested = false;
  std::chrono::steady_clock::time_point m_start;
  std::thread m_reader, m_killer;
};

}  // namespace forensim
