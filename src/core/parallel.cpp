#include "core/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <mutex>

namespace forensim {
namespace {
std::mutex g_control_mutex;
std::unique_ptr<tbb::global_control> g_control;

// Every loop runs in its own isolated context. With TBB's default (a context bound to the enclosing task's),
// an exception in one branch of an outer algorithm cancels the whole tree: a nested loop still running in a
// sibling branch then returns early with iterations silently skipped, and the sibling goes on with
// half-filled arrays (a reader failing beside the template build crashed `reconstruct` that way). Isolated,
// a loop either runs every iteration or throws.
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
  tbb::task_group_context ctx(tbb::task_group_context::isolated);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(begin, end, grain == 0 ? 1 : grain),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
      },
      ctx);
}

void parallel_invoke(const std::function<void()>& first, const std::function<void()>& second) {
  // Both branches run to the end even when one throws (neither is cancelled half-way), then the first
  // branch's exception wins over the second's, whichever thread finished first.
  std::exception_ptr first_error, second_error;
  tbb::task_group_context ctx(tbb::task_group_context::isolated);
  tbb::parallel_invoke(
      [&] {
        try {
          first();
        } catch (...) {
          first_error = std::current_exception();
        }
      },
      [&] {
        try {
          second();
        } catch (...) {
          second_error = std::current_exception();
        }
      },
      ctx);
  if (first_error) std::rethrow_exception(first_error);
  if (second_error) std::rethrow_exception(second_error);
}

void parallel_for_chunks(std::size_t begin, std::size_t end, const std::function<void(std::size_t, std::size_t)>& body,
                         std::size_t grain) {
  if (begin >= end) return;
  tbb::task_group_context ctx(tbb::task_group_context::isolated);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(begin, end, grain == 0 ? 1 : grain),
      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); }, ctx);
}

double parallel_sum(std::size_t begin, std::size_t end, const std::function<double(std::size_t)>& f,
                    std::size_t block) {
  if (begin >= end) return 0.0;
  if (block == 0) block = 1;
  const std::size_t blocks = (end - begin + block - 1) / block;
  std::vector<double> partial(blocks, 0.0);
  tbb::task_group_context ctx(tbb::task_group_context::isolated);
  tbb::parallel_for(
      std::size_t{0}, blocks,
      [&](std::size_t b) {
        const std::size_t lo = begin + b * block;
        const std::size_t hi = std::min(end, lo + block);
        double s = 0.0;
        for (std::size_t i = lo; i < hi; ++i) s += f(i);
        partial[b] = s;
      },
      ctx);
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
  tbb::task_group_context ctx(tbb::task_group_context::isolated);
  tbb::parallel_for(
      std::size_t{0}, blocks,
      [&](std::size_t b) {
        const std::size_t lo = begin + b * block;
        partial[b] = chunk(lo, std::min(end, lo + block));
      },
      ctx);
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

}  // namespace forensim
