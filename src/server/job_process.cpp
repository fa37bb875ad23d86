#include "server/job_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <regex>

#include "core/error.hpp"

namespace forensim {

namespace {
constexpr std::size_t kKeptLines = 40;
}

std::optional<ProgressLine> parse_progress_line(const std::string& line) {
  static const std::regex running(R"(^(.+): (\d+)% \((\d+)/(\d+)\) eta .*$)");
  static const std::regex started(R"(^(.+): started \((\d+) steps\)$)");
  static const std::regex finished(R"(^(.+): (\d+)/(\d+) done in .*$)");
  std::smatch m;
  try {
    if (std::regex_match(line, m, running)) {
      return ProgressLine{m[1].str(), std::stoull(m[3].str()), std::stoull(m[4].str())};
    }
    if (std::regex_match(line, m, started)) return ProgressLine{m[1].str(), 0, std::stoull(m[2].str())};
    if (std::regex_match(line, m, finished)) {
      return ProgressLine{m[1].str(), std::stoull(m[2].str()), std::stoull(m[3].str())};
    }
  } catch (const std::exception&) {  // numbers out of range: not a progress line of ours
  }
  return std::nullopt;
}

JobProcess::JobProcess(const std::filesystem::path& executable, const std::vector<std::string>& arguments,
                       const std::filesystem::path& working_dir)
    : m_start(std::chrono::steady_clock::now()) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw IoError(executable.string(), std::string("pipe: ") + std::strerror(errno));
  // Everything the child needs is prepared before fork: after it only async-signal-safe calls are allowed.
  const std::string exe = executable.string(), cwd = working_dir.string();
  std::vector<std::string> args;
  args.push_back(exe);
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw IoError(exe, std::string("cannot start a job process: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::setpgid(0, 0);  // the server's terminal Ctrl-C goes to the server, which cancels its jobs
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::signal(SIGPIPE, SIG_DFL);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, 0);
    ::dup2(fds[1], 1);
    ::dup2(fds[1], 2);
    ::close_range(3, ~0U, 0);  // no listening socket or other job's pipe leaks into the child
    if (::chdir(cwd.c_str()) != 0) ::_exit(126);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  m_pid = pid;
  const int read_fd = fds[0];
  m_reader = std::thread([this, read_fd] { read_output(read_fd); });
}

JobProcess::~JobProcess() {
  {
    std::unique_lock lock(m_mutex);
    if (m_snapshot.state == ProcessState::running && !m_cancel_requested) {
      lock.unlock();
      cancel(1.0);
    }
  }
  if (m_reader.joinable()) m_reader.join();
  if (m_killer.joinable()) m_killer.join();
}

void JobProcess::read_output(int fd) {
  std::string partial;
  char buffer[4096];
  auto take_line = [&](std::string line) {
    if (line.empty()) return;
    std::lock_guard lock(m_mutex);
    if (auto p = parse_progress_line(line)) m_snapshot.progress = *p;
    if (line.rfind("forensim: error: ", 0) == 0) m_snapshot.error = line.substr(17);
    m_lines.push_back(std::move(line));
    while (m_lines.size() > kKeptLines) m_lines.pop_front();
  };
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    for (ssize_t i = 0; i < n; ++i) {
      const char c = buffer[i];
      if (c == '\n' || c == '\r') {
        take_line(std::move(partial));
        partial.clear();
      } else if (partial.size() < 4096) {
        partial.push_back(c);
      }
    }
  }
  take_line(std::move(partial));
  ::close(fd);
  // Wait without reaping, then reap under the lock: cancel() never signals a pid that was reaped.
  siginfo_t info{};
  while (::waitid(P_PID, static_cast<id_t>(m_pid), &info, WEXITED | WNOWAIT) != 0 && errno == EINTR) {
  }
  std::lock_guard lock(m_mutex);
  int status = 0;
  while (::waitpid(m_pid, &status, 0) < 0 && errno == EINTR) {
  }
  m_snapshot.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (m_cancel_requested || m_snapshot.exit_code == 130) {
    m_snapshot.state = ProcessState::cancelled;
  } else if (m_snapshot.exit_code == 0) {
    m_snapshot.state = ProcessState::succeeded;
  } else {
    m_snapshot.state = ProcessState::failed;
    if (m_snapshot.error.empty()) {
      m_snapshot.error = m_snapshot.exit_code == 127 ? "the forensim executable could not be run"
                                                     : "exited with code " + std::to_string(m_snapshot.exit_code);
    }
  }
  m_snapshot.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  m_ended.notify_all();
}

ProcessSnapshot JobProcess::snapshot() const {
  std::lock_guard lock(m_mutex);
  ProcessSnapshot s = m_snapshot;
  s.last_lines.assign(m_lines.begin(), m_lines.end());
  if (s.state == ProcessState::running) {
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  }
  return s;
}

void JobProcess::cancel(double grace_seconds) {
  std::lock_guard lock(m_mutex);
  if (m_snapshot.state != ProcessState::running || m_cancel_requested) return;
  m_cancel_requested = true;
  ::kill(m_pid, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                                               std::chrono::duration<double>(grace_seconds));
  m_killer = std::thread([this, deadline] {
    std::unique_lock killer_lock(m_mutex);
    if (!m_ended.wait_until(killer_lock, deadline, [this] { return m_snapshot.state != ProcessState::running; })) {
      ::kill(m_pid, SIGKILL);
    }
  });
}

bool JobProcess::wait_for(double seconds) const {
  std::unique_lock lock(m_mutex);
  return m_ended.wait_for(lock, std::chrono::duration<double>(seconds),
                          [this] { return m_snapshot.state != ProcessState::running; });
}

}  // namespace forensim
