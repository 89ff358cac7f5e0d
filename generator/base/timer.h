// Wall-clock timing of pipeline stages, for the timings that --stats, the scene statistics and
// the benchmarks report. Timings are reported only: no result depends on them.
#pragma once

#include <chrono>

namespace cutaway {

/// Seconds of wall time (steady clock) since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace cutaway
