#include "core/crash_report.hpp"

#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>

namespace forensim {
namespace {

constexpr int kMaxDepth = 16;
constexpr std::size_t kMaxText = 256;

// Fixed storage, so the handler reads it without allocating. Each level is written before the depth that
// makes it visible is published.
std::array<std::array<char, kMaxText>, kMaxDepth> g_activities{};
std::atomic<int> g_depth{0};
const char* g_program = "forensim";
std::atomic<bool> g_installed{false};

void write_text(const char* text) {
  const std::size_t n = std::strlen(text);
  std::size_t done = 0;
  while (done < n) {
    const ssize_t w = ::write(STDERR_FILENO, text + done, n - done);
    if (w <= 0) return;
    done += static_cast<std::size_t>(w);
  }
}

const char* signal_text(int sig) {
  switch (sig) {
    case SIGSEGV:
      return "segmentation fault (SIGSEGV)";
    case SIGBUS:
      return "bus error (SIGBUS)";
    case SIGILL:
      return "illegal instruction (SIGILL)";
    case SIGFPE:
      return "floating-point exception (SIGFPE)";
    case SIGABRT:
      return "abort (SIGABRT)";
    default:
      return "fatal signal";
  }
}

void on_fatal_signal(int sig) {
  // Only async-signal-safe calls here: write(2) and backtrace_symbols_fd (libgcc is loaded beforehand).
  write_text("\n");
  write_text(g_program);
  write_text(": crashed: ");
  write_text(signal_text(sig));
  const int depth = std::min(g_depth.load(), kMaxDepth);
  if (depth > 0) {
    write_text(" while ");
    write_text(g_activities[static_cast<std::size_t>(depth - 1)].data());
    for (int i = depth - 2; i >= 0; --i) {
      write_text(", in ");
      write_text(g_activities[static_cast<std::size_t>(i)].data());
    }
  }
  write_text(".\nThis is a bug in forensim; please report it with the command line and this trace:\n");
  void* frames[64];
  const int n = backtrace(frames, 64);
  backtrace_symbols_fd(frames, n, STDERR_FILENO);
  // End as the signal would have: default action, raised again on return from the handler.
  signal(sig, SIG_DFL);
  raise(sig);
}

}  // namespace

void install_crash_handler(const char* program) {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reports fatal signals itself, with the faulting address and a symbolised stack: its handler
  // stays.
  static_cast<void>(program);
  return;
#endif
  if (g_installed.exchange(true)) return;
  g_program = program;
  // backtrace() loads libgcc on its first call, which allocates: do it now, not in the handler.
  void* warm[1];
  backtrace(warm, 1);
  // An own stack, so a stack overflow can still be reported.
  static std::array<char, 64 * 1024> stack{};
  stack_t ss{};
  ss.ss_sp = stack.data();
  ss.ss_size = stack.size();
  ss.ss_flags = 0;
  sigaltstack(&ss, nullptr);
  struct sigaction action {};
  action.sa_handler = on_fatal_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_ONSTACK | SA_RESETHAND;
  for (const int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) sigaction(sig, &action, nullptr);
}

CrashActivity::CrashActivity(std::string_view activity) : m_depth(g_depth.load()) {
  if (m_depth < kMaxDepth) {
    auto& slot = g_activities[static_cast<std::size_t>(m_depth)];
    const std::size_t n = std::min(activity.size(), kMaxText - 1);
    std::memcpy(slot.data(), activity.data(), n);
    slot[n] = '\0';
  }
  g_depth.store(m_depth + 1);
}

CrashActivity::~CrashActivity() {
  g_depth.store(m_depth);
}

std::string_view current_crash_activity() {
  const int depth = std::min(g_depth.load(), kMaxDepth);
  return depth == 0 ? std::string_view{} : std::string_view(g_activities[static_cast<std::size_t>(depth - 1)].data());
}

}  // namespace forensim
