// The stage timers: a thread's processor time counts its own work and not its waits.
#include "base/timer.h"

#include <chrono>
#include <cstdint>
#include <thread>

#include <gtest/gtest.h>

namespace cutaway {
namespace {

// Sleeping takes wall time but hardly any processor time; a fixed amount of work (a count of
// steps, not a span of wall time) takes processor time whatever else runs on the machine. The
// test compares the clocks with each other, never with a bound in seconds: on a loaded machine
// the work takes longer, but not less processor time than a sleep.
TEST(Timer, ThreadProcessorSecondsCountWorkNotWaiting) {
  const double slept_from = thread_processor_seconds();
  const auto wall_from = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const double slept = thread_processor_seconds() - slept_from;
  const double slept_wall = seconds_since(wall_from);
  // sleep_for waits at least what it is asked: the wall clock counts all of it.
  EXPECT_GE(slept_wall, 0.2);
  // A sleeping thread uses next to no processor time (measured: about 50 microseconds of the
  // 0.2 s); a clock that ran on while it waited would count most of the sleep.
  EXPECT_LT(slept, slept_wall / 4) << "the sleep counted as work";

  // 10^8 dependent additions (each through memory, as `sink` is volatile): measured 0.04 to
  // 0.06 s of processor time, a thousand times the sleep's, however long they take on the wall.
  const auto spin_from = std::chrono::steady_clock::now();
  const double spun_from = thread_processor_seconds();
  volatile uint64_t sink = 0;
  for (uint64_t step = 0; step < 100'000'000; ++step) sink = sink + 1;
  const double spun = thread_processor_seconds() - spun_from;
  const double spun_wall = seconds_since(spin_from);
  EXPECT_EQ(sink, 100'000'000u);
  EXPECT_GT(spun, slept) << "the work counted less than the sleep";
  // One thread's processor time never runs ahead of the wall clock, read around it (1 % for
  // the two clocks' sources; a unit mistake would be a factor of 1000).
  EXPECT_LE(spun, 1.01 * spun_wall);
}

}  // namespace
}  // namespace cutaway
