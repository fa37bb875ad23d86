#include "server/job_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>

#include "core/error.hpp"

namespace forensim {

namespace {
constexpr std::size_t kKeptLines = 40;
}

namespace {

/// Reads an unsigned decimal at `text[pos]`, advancing `pos`; nothing when no digit is there or it overflows.
std::optional<std::uint64_t> read_count(std::string_view text, std::size_t& pos) {
  const std::size_t begin = pos;
  std::uint64_t value = 0;
  while (pos < text.size() && text[pos] >= '0' && text[pos] <= '9') {
    const std::uint64_t digit = static_cast<std::uint64_t>(text[pos] - '0');
    if (value > (std::numeric_limits<std::uint64_t>::max() - digit) / 10) return std::nullopt;
    value = value * 10 + digit;
    ++pos;
  }
  if (pos == begin) return std::nullopt;
  return value;
}

/// Consumes `literal` at `text[pos]`.
bool read_literal(std::string_view text, std::size_t& pos, std::string_view literal) {
  if (text.substr(pos, literal.size()) != literal) return false;
  pos += literal.size();
  return true;
}

/// Parses the part after "label: " in one of the three progress forms.
std::optional<ProgressLine> parse_progress_rest(const std::string& label, std::string_view rest) {
  std::size_t pos = 0;
  if (read_literal(rest, pos, "started (")) {  // "started (N steps)"
    const auto steps = read_count(rest, pos);
    if (steps && read_literal(rest, pos, " steps)") && pos == rest.size()) return ProgressLine{label, 0, *steps};
    return std::nullopt;
  }
  const auto first = read_count(rest, pos);
  if (!first) return std::nullopt;
  if (read_literal(rest, pos, "% (")) {  // "P% (D/N) eta ..."
    const auto done = read_count(rest, pos);
    if (!done || !read_literal(rest, pos, "/")) return std::nullopt;
    const auto total = read_count(rest, pos);
    if (total && read_literal(rest, pos, ") eta ")) return ProgressLine{label, *done, *total};
    return std::nullopt;
  }
  if (read_literal(rest, pos, "/")) {  // "D/N done in ..."
    const auto total = read_count(rest, pos);
    if (total && read_literal(rest, pos, " done in ")) return ProgressLine{label, *first, *total};
  }
  return std::nullopt;
}

}  // namespace

std::optional<ProgressLine> parse_progress_line(const std::string& line) {
  // The label may itself hold ": ", so every split point is tried from the last (the label is the longest
  // prefix that leaves a well-formed rest, as a greedy "(.+): " would take it).
  for (std::size_t split = line.rfind(": "); split != std::string::npos && split > 0;
       split = split == 0 ? std::string::npos : line.rfind(": ", split - 1)) {
    if (auto parsed = parse_progress_rest(line.substr(0, split), std::string_view(line).substr(split + 2))) {
      return parsed;
    }
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
