#pragma once
/// A report for the one failure that cannot become an Error: a fatal signal (segmentation fault, bus
/// error, illegal instruction, floating-point trap, abort). The handler writes, to stderr, which signal
/// it was, what forensim was doing (the innermost CrashActivity) and a backtrace of the crashing thread,
/// then lets the signal end the process as it would have (same exit status, core dump if enabled).
/// Users paste this into a bug report; CI logs show where a crash happened instead of only
/// "Segmentation fault". It runs on its own signal stack, so a stack overflow is reported too.

#include <string_view>

namespace forensim {

/// Installs the handler for SIGSEGV, SIGBUS, SIGILL, SIGFPE and SIGABRT. `program` names the program in
/// the report ("forensim"). Installing twice is harmless. Under AddressSanitizer it does nothing (the
/// sanitizer's own report of a fatal signal says more).
void install_crash_handler(const char* program);

/// Names what the process is doing, for the crash report, while it lives ("demo stage 'template'");
/// nests: the previous activity is shown again when this one ends. Set from the main thread; a crash in
/// a worker thread reports the main thread's activity. Longer texts are cut at 255 bytes.
class CrashActivity {
 public:
  explicit CrashActivity(std::string_view activity);
  ~CrashActivity();
  CrashActivity(const CrashActivity&) = delete;
  CrashActivity& operator=(const CrashActivity&) = delete;

 private:
  int m_depth;
};

/// The innermost activity now ("" when none), as the crash report would print it.
std::string_view current_crash_activity();

}  // namespace forensim
