#include "core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <utility>

namespace forensim {
namespace {
std::atomic<ProgressStyle> g_style{ProgressStyle::automatic};
volatile std::sig_atomic_t g_interrupt = 0;

void on_signal(int signal_number) {
  if (g_interrupt) std::_Exit(128 + signal_number);
  g_interrupt = 1;
}

ProgressStyle resolve(ProgressStyle s) {
  if (s != ProgressStyle::automatic) return s;
  return isatty(STDERR_FILENO) ? ProgressStyle::bar : ProgressStyle::lines;
}
}  // namespace

void set_progress_style(ProgressStyle style) {
  g_style = style;
}

std::string format_duration(double seconds) {
  char buf[64];
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 60) {
    std::snprintf(buf, sizeof buf, "%.1fs", seconds);
  } else if (seconds < 3600) {
    const int s = static_cast<int>(seconds);
    std::snprintf(buf, sizeof buf, "%dm%02ds", s / 60, s % 60);
  } else {
    const int m = static_cast<int>(seconds / 60);
    std::snprintf(buf, sizeof buf, "%dh%02dm", m / 60, m % 60);
  }
  return buf;
}

Progress::Progress(std::string label, std::size_t total)
    : m_label(std::move(label)),
      m_total(std::max<std::size_t>(total, 1)),
      m_start(std::chrono::steady_clock::now()),
      m_last_draw(m_start),
      m_style(resolve(g_style.load())) {
  if (m_style == ProgressStyle::lines) {
    std::fprintf(stderr, "%s: started (%zu steps)\n", m_label.c_str(), m_total);
  }
}

Progress::~Progress() {
  finish();
}

void Progress::set_done(std::size_t done) {
  m_done = std::min(done, m_total);
  m_start_done = m_done;
  m_start = std::chrono::steady_clock::now();
}

void Progress::advance(std::size_t units) {
  m_done.fetch_add(units);
  if (m_style == ProgressStyle::quiet) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - m_last_draw).count();
  const double min_interval = m_style == ProgressStyle::bar ? 0.1 : 5.0;
  if (since < min_interval) return;
  std::unique_lock lock(m_mutex, std::try_to_lock);
  if (!lock.owns_lock() || m_finished) return;
  m_last_draw = now;
  draw(false);
}

void Progress::finish() {
  std::lock_guard lock(m_mutex);
  if (m_finished) return;
  m_finished = true;
  if (m_style != ProgressStyle::quiet) draw(true);
}

void Progress::draw(bool final_line) {
  const std::size_t done = std::min(m_done.load(), m_total);
  const double fraction = static_cast<double>(done) / static_cast<double>(m_total);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  const std::size_t fresh = done - std::min(done, m_start_done);
  const double eta = fresh > 0 ? elapsed / static_cast<double>(fresh) * static_cast<double>(m_total - done) : -1;
  if (m_style == ProgressStyle::bar) {
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r%s [%s] %3d%% %zu/%zu %s %s%s", m_label.c_str(), bar.c_str(),
                 static_cast<int>(fraction * 100), done, m_total, final_line ? "took" : "eta",
                 final_line ? format_duration(elapsed).c_str() : format_duration(eta).c_str(),
                 final_line ? "\n" : "   ");
  } else {
    if (final_line) {
      std::fprintf(stderr, "%s: %zu/%zu done in %s\n", m_label.c_str(), done, m_total,
                   format_duration(elapsed).c_str());
    } else {
      std::fprintf(stderr, "%s: %d%% (%zu/%zu) eta %s\n", m_label.c_str(), static_cast<int>(fraction * 100), done,
                   m_total, format_duration(eta).c_str());
    }
  }
  std::fflush(stderr);
}

void install_interrupt_handler() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupt_requested() {
  return g_interrupt != 0;
}
void set_interrupt_requested(bool requested) {
  g_interrupt = requested ? 1 : 0;
}

}  // namespace forensim
