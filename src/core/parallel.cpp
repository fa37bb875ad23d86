#include "core/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <memory>
#include <mutex>

namespace forensim {
namespace {
std::mutex g_control_mutex;
std::unique_ptr<tbb::global_control> g_control;
}  // namespace

void set_thread_count(int threads) {
  std::lock_guard lock(g_control_mutex);
  g_control.reset();
  if (threads > 0) {
    g_control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<std::size_t>(threads));
  }
}

int thread_count() {
  return static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

void parallel_for(std::size_t begin, std::size_t end, const std::function<void(std::size_t)>& body, std::size_t grain) {
  if (begin >= end) return;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, grain == 0 ? 1 : grain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
                    });
}

void parallel_invoke(const std::function<void()>& first, const std::function<void()>& second) {
  tbb::parallel_invoke(first, second);
}

void parallel_for_chunks(std::size_t begin, std::size_t end, const std::function<void(std::size_t, std::size_t)>& body,
                         std::size_t grain) {
  if (begin >= end) return;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, grain == 0 ? 1 : grain),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

double parallel_sum(std::size_t begin, std::size_t end, const std::function<double(std::size_t)>& f,
                    std::size_t block) {
  if (begin >= end) return 0.0;
  if (block == 0) block = 1;
  const std::size_t blocks = (end - begin + block - 1) / block;
  std::vector<double> partial(blocks, 0.0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    const std::size_t lo = begin + b * block;
    const std::size_t hi = std::min(end, lo + block);
    double s = 0.0;
    for (std::size_t i = lo; i < hi; ++i) s += f(i);
    partial[b] = s;
  });
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

double parallel_sum_chunks(std::size_t begin, std::size_t end,
                           const std::function<double(std::size_t, std::size_t)>& chunk, std::size_t block) {
  if (begin >= end) return 0.0;
  if (block == 0) block = 1;
  const std::size_t blocks = (end - begin + block - 1) / block;
  if (blocks == 1) return chunk(begin, end);
  std::vector<double> partial(blocks, 0.0);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    const std::size_t lo = begin + b * block;
    partial[b] = chunk(lo, std::min(end, lo + block));
  });
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

}  // namespace forensim
