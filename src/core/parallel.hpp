#pragma once
/// Parallel loops on oneTBB. Reductions are deterministic: the range is cut into fixed blocks that do not
/// depend on the thread count and block results are combined in order, so sums are bitwise identical at
/// any thread count.
///
/// Every loop runs in an isolated TBB context: an exception in one loop ends that loop (rethrown from the call)
/// and never cancels a loop running elsewhere, so a loop returns either with every iteration done or by
/// throwing, never with iterations silently skipped.

#include <cstddef>
#include <functional>
#include <vector>

namespace forensim {

/// Limits the worker threads used by forensim (0 = all hardware threads). Lasts until called again.
void set_thread_count(int threads);
/// Threads forensim currently uses.
int thread_count();

/// Calls body(i) for every i in [begin, end), in parallel. `grain` is the smallest chunk given to one task.
void parallel_for(std::size_t begin, std::size_t end, const std::function<void(std::size_t)>& body,
                  std::size_t grain = 256);

/// Calls first() and second() side by side (two independent pieces of work), returning when both are done. Both
/// run to the end even when the other throws; then first()'s exception is rethrown here, else second()'s.
void parallel_invoke(const std::function<void()>& first, const std::function<void()>& second);

/// Calls body(chunk_begin, chunk_end) over [begin, end) cut into chunks of at most `grain`.
void parallel_for_chunks(std::size_t begin, std::size_t end, const std::function<void(std::size_t, std::size_t)>& body,
                         std::size_t grain = 1024);

/// Deterministic sum of f(i) over [begin, end): fixed blocks of `block` items summed serially, then the
/// block sums added in block order.
double parallel_sum(std::size_t begin, std::size_t end, const std::function<double(std::size_t)>& f,
                    std::size_t block = 4096);

/// Deterministic sum of chunk(lo, hi) over [begin, end) cut into fixed blocks of `block` items (the last one
/// shorter): one call per block, in parallel, then the block results added in block order. For loops whose
/// body is too small for a call per item (vector dot products).
double parallel_sum_chunks(std::size_t begin, std::size_t end,
                           const std::function<double(std::size_t, std::size_t)>& chunk, std::size_t block = 4096);

}  // namespace forensim
