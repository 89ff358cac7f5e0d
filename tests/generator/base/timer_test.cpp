// The stage timers: a thread's processor time counts its own work and not its waits.
#include "base/timer.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

namespace cutaway {
namespace {

// Sleeping takes wall time but hardly any processor time; spinning takes both.
TEST(Timer, ThreadProcessorSecondsCountWorkNotWaiting) {
  const double slept_from = thread_processor_seconds();
  const auto wall_from = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const double slept = thread_processor_seconds() - slept_from;
  EXPECT_GE(seconds_since(wall_from), 0.2);
  EXPECT_LT(slept, 0.05);

  // 0.2 s of spinning: most of it on a core even when other tests share the machine.
  const double spun_from = thread_processor_seconds();
  const auto spin_from = std::chrono::steady_clock::now();
  volatile double sink = 0;
  while (seconds_since(spin_from) < 0.2) sink = sink + 1;
  EXPECT_GT(thread_processor_seconds() - spun_from, 0.02);
  EXPECT_GT(sink, 0);
}

}  // namespace
}  // namespace cutaway
