// Timing of pipeline stages (wall clock, or a thread's processor time), for the timings that
// --stats, the scene statistics and the benchmarks report. Timings are reported only: no result
// depends on them.
#pragma once

#include <chrono>
#include <ctime>

namespace cutaway {

/// Seconds of wall time (steady clock) since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Processor seconds the calling thread has used so far (CLOCK_THREAD_CPUTIME_ID): the
/// difference of two calls on one thread is the work done between them, without the time the
/// thread waited for a core while other threads ran.
inline double thread_processor_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace cutaway
