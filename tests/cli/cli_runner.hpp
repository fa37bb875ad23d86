#pragma once
/// Runs the forensim command line from tests and captures its exit code and output: the executable, or, in
/// run_cli_timed where the tests link the command line, the same code in a forked child.

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#if defined(FORENSIM_CLI_IN_PROCESS)
#include "forensim/cli_main.hpp"
#endif

namespace forensim::test {

struct CliResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `forensim <arguments>` through the shell (arguments are passed as written).
inline CliResult run_cli(const std::string& arguments) {
  const std::string command = std::string(FORENSIM_CLI_PATH) + " --progress quiet " + arguments + " 2>&1";
  CliResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

/// How a time-limited run of forensim ended.
struct TimedCliResult {
  int exit_code = -1;       ///< exit status; -1 when a signal ended the process or it could not start
  int exec_errno = 0;       ///< why the executable could not be started (errno of execv); 0 when it started
  int signal = 0;           ///< the signal that ended it (0: it exited); SIGKILL from the time limit is not counted
  bool timed_out = false;   ///< still running after the time limit, then killed (with its process group)
  bool in_process = false;  ///< run by a forked copy of this process, not by the executable (see above)
  double seconds = 0.0;     ///< wall-clock time of the run
  std::string output;       ///< stdout and stderr together
};

/// The number of threads of this process (/proc/self/status); 0 when it cannot be read.
inline int thread_count() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("Threads:", 0) == 0) return std::atoi(line.c_str() + 8);
  }
  return 0;
}

/// Ends the idle worker threads that two libraries start as they load, so that a test process that has run
/// nothing else is single-threaded and may fork the command line: log4cplus's thread pool (loaded with
/// OpenVDB; no forensim code logs through it) and OpenBLAS's server threads (which OpenBLAS itself ends
/// before every fork, and starts again when next needed). Each is looked up by its exported name and skipped
/// where the library is not loaded; any other thread keeps run_cli_timed on exec.
inline void end_library_threads() {
  if (void* pool = dlsym(RTLD_DEFAULT, "_ZN9log4cplus18shutdownThreadPoolEv")) {  // log4cplus::shutdownThreadPool()
    reinterpret_cast<void (*)()>(pool)();
  }
  if (void* blas = dlsym(RTLD_DEFAULT, "blas_thread_shutdown_")) reinterpret_cast<int (*)()>(blas)();
}

/// One try of run_cli_timed.
inline TimedCliResult run_cli_timed_once(const std::vector<std::string>& arguments, double timeout_s) {
  using clock = std::chrono::steady_clock;
  TimedCliResult result;
  std::vector<std::string> words = {FORENSIM_CLI_PATH, "--progress", "quiet"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  int fds[2], exec_fds[2];  // output; execv's errno (closed unwritten by a successful exec)
  if (pipe2(fds, O_CLOEXEC) != 0) return result;
  if (pipe2(exec_fds, O_CLOEXEC) != 0) {
    close(fds[0]);
    close(fds[1]);
    return result;
  }
  const int null_fd = open("/dev/null", O_RDONLY | O_CLOEXEC);
  // Where the tests link the command line (FORENSIM_CLI_IN_PROCESS), the child runs it without exec: the
  // same code as the executable's main, less the 0.15 s that starting the executable takes (dynamic loading
  // of 69 libraries and their static initialisation). Only from a single-threaded process (a thread pool does
  // not survive fork), and not for serve, which starts jobs as /proc/self/exe.
#if defined(FORENSIM_CLI_IN_PROCESS)
  static const bool library_threads_ended = (end_library_threads(), true);
  const bool in_process =
      library_threads_ended && thread_count() == 1 && (arguments.empty() || arguments.front() != "serve");
#else
  const bool in_process = false;
#endif
  std::fflush(nullptr);  // nothing buffered here is written twice by the child
  const auto start = clock::now();
  const pid_t pid = fork();
  if (pid == 0) {  // only async-signal-safe calls from here to exec
    setpgid(0, 0);
    if (null_fd >= 0) dup2(null_fd, 0);
    dup2(fds[1], 1);
    dup2(fds[1], 2);
#if defined(FORENSIM_CLI_IN_PROCESS)
    if (in_process) {  // a single-threaded parent: the child may run anything
      const int code = forensim::cli::run_main(static_cast<int>(argv.size()) - 1, argv.data());
      std::fflush(nullptr);
      _exit(code);
    }
#endif
    execv(argv[0], argv.data());
    const int error = errno;
    [[maybe_unused]] const ssize_t written = write(exec_fds[1], &error, sizeof error);
    _exit(127);
  }
  close(fds[1]);
  close(exec_fds[1]);
  if (null_fd >= 0) close(null_fd);
  if (pid < 0) {
    close(fds[0]);
    close(exec_fds[0]);
    return result;
  }
  setpgid(pid, pid);  // also here, so the group exists before any kill below
  const auto deadline = start + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(timeout_s));
  char buffer[4096];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock::now()).count();
    if (left <= 0) {
      result.timed_out = true;
      kill(-pid, SIGKILL);
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of output: every writer has closed the pipe
    result.output.append(buffer, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  // A process that closed its output may still run: wait for it up to the same deadline.
  while (!result.timed_out && waitpid(pid, &status, WNOHANG) == 0) {
    if (clock::now() >= deadline) {
      result.timed_out = true;
      kill(-pid, SIGKILL);
      break;
    }
    usleep(10000);
  }
  if (result.timed_out) {
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
  }
  result.seconds = std::chrono::duration<double>(clock::now() - start).count();
  result.in_process = in_process;
  int error = 0;
  if (read(exec_fds[0], &error, sizeof error) == static_cast<ssize_t>(sizeof error)) result.exec_errno = error;
  close(exec_fds[0]);
  if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status) && !(result.timed_out && WTERMSIG(status) == SIGKILL)) {
    result.signal = WTERMSIG(status);
  }
  return result;
}

/// Runs `forensim --progress quiet <arguments>` without a shell (each argument passed as it is), stdin from
/// /dev/null, in a process group of its own that is killed with SIGKILL after `timeout_s` seconds. While the
/// executable cannot be started (a build relinking it beside the tests) it tries again, for up to a minute.
inline TimedCliResult run_cli_timed(const std::vector<std::string>& arguments, double timeout_s) {
  TimedCliResult result = run_cli_timed_once(arguments, timeout_s);
  for (int attempt = 0; attempt < 60 && result.exec_errno != 0; ++attempt) {
    usleep(1000000);
    result = run_cli_timed_once(arguments, timeout_s);
  }
  return result;
}

}  // namespace forensim::test
