// Work over an index range on TBB's threads, within a thread budget: the loop every sampler
// that honours a `threads` setting (0: all cores) shares.
#pragma once

#include <cstddef>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

namespace cutaway {

/// Runs body(begin, end) over disjoint chunks covering [0, n), of at least `grain` indices
/// where n allows, on `threads` worker threads (0: all cores; otherwise in a task arena of
/// that many). Chunks run in any order and at once: `body` must not depend on either.
template <typename Body>
void parallel_chunks(size_t n, size_t grain, int threads, Body body) {
  auto run = [&] {
    oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<size_t>(0, n, grain),
                              [&](const oneapi::tbb::blocked_range<size_t>& r) {
                                body(r.begin(), r.end());
                              });
  };
  if (threads > 0) {
    oneapi::tbb::task_arena arena(threads);
    arena.execute(run);
  } else {
    run();
  }
}

}  // namespace cutaway
