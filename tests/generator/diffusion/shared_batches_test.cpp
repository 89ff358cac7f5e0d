// Shared diffusion batches (diffusion/shared_batches.h): tasks running at once get what the
// backend gives each point, their rounds are served together on the calling thread, and errors
// reach the caller without leaving a thread waiting.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <functional>
#include <mutex>
#include <string>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "base/error.h"
#include "diffusion/shared_batches.h"

namespace cutaway {
namespace {

/// The colour and material channels RecordingBackend gives point p.
glm::dvec3 recorded_colour(const glm::dvec3& p) { return {p.x * 2, p.y + 1, p.z}; }
glm::dvec2 recorded_material(const glm::dvec3& p) { return {p.x, -p.y}; }

/// A backend whose colour is a function of the point alone, recording its calls.
class RecordingBackend final : public DiffusionBackend {
 public:
  void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                        std::span<glm::dvec2> material) const override {
    check_channel_sizes(points.size(), colour.size(), material.size());
    const std::lock_guard lock(mutex_);
    if (fail_after >= 0 && static_cast<int>(batch_sizes.size()) >= fail_after)
      throw std::runtime_error("backend gave up");
    batch_sizes.push_back(points.size());
    threads.push_back(std::this_thread::get_id());
    for (size_t i = 0; i < points.size(); ++i) {
      colour[i] = recorded_colour(points[i]);
      if (!material.empty()) material[i] = recorded_material(points[i]);
    }
  }
  std::string name() const override { return "recording"; }

  int fail_after = -1;  ///< throw from this call on (-1: never)
  mutable std::vector<size_t> batch_sizes;
  mutable std::vector<std::thread::id> threads;

 private:
  mutable std::mutex mutex_;
};

/// Task i's round r: i + 1 points, with material channels on even rounds.
std::vector<glm::dvec3> round_points(size_t task, int round) {
  std::vector<glm::dvec3> p;
  for (size_t k = 0; k <= task; ++k)
    p.emplace_back(static_cast<double>(task), round, static_cast<double>(k));
  return p;
}

/// What each task of a run did: the thread it ran on, its diffusion calls and the values it
/// got wrong.
struct TaskLog {
  explicit TaskLog(size_t tasks) : wrong(tasks, 0), calls(tasks, 0), ran_on(tasks) {}
  std::vector<int> wrong, calls;
  std::vector<std::thread::id> ran_on;

  /// A task that diffuses the colours of round_points(task % sizes, r) for r < rounds, one
  /// call per round, and checks them against recorded_colour.
  std::function<void(size_t, const DiffusionBackend&)> task(int rounds, size_t sizes) {
    return [this, rounds, sizes](size_t task, const DiffusionBackend& diffusion) {
      ran_on[task] = std::this_thread::get_id();
      for (int round = 0; round < rounds; ++round) {
        const std::vector<glm::dvec3> points = round_points(task % sizes, round);
        std::vector<glm::dvec3> colour(points.size());
        diffusion.diffuse_channels(points, colour, {});
        ++calls[task];
        for (size_t k = 0; k < points.size(); ++k)
          wrong[task] += colour[k] != recorded_colour(points[k]);
      }
    };
  }
};

TEST(SharedBatches, TasksGetTheBackendsValuesInFewerCallsOnTheCallingThread) {
  RecordingBackend backend;
  constexpr size_t kTasks = 6;
  std::vector<int> wrong(kTasks, 0);
  const SharedBatchStats stats = run_with_shared_batches(
      backend, kTasks,
      [&](size_t task, const DiffusionBackend& diffusion) {
        // Task i makes i + 1 rounds, so tasks drop out one by one.
        for (int round = 0; round <= static_cast<int>(task); ++round) {
          const std::vector<glm::dvec3> points = round_points(task, round);
          std::vector<glm::dvec3> colour(points.size());
          std::vector<glm::dvec2> material(round % 2 == 0 ? points.size() : 0);
          diffusion.diffuse_channels(points, colour, material);
          for (size_t k = 0; k < points.size(); ++k) {
            wrong[task] += colour[k] != recorded_colour(points[k]);
            if (!material.empty()) wrong[task] += material[k] != recorded_material(points[k]);
          }
        }
      },
      16);
  for (size_t i = 0; i < kTasks; ++i) EXPECT_EQ(wrong[i], 0) << "task " << i;
  // Round r is one batch of the tasks still running: rounds 0..5, one call each.
  ASSERT_EQ(backend.batch_sizes.size(), kTasks);
  for (size_t r = 0; r < kTasks; ++r) {
    size_t expected = 0;
    for (size_t i = r; i < kTasks; ++i) expected += i + 1;
    EXPECT_EQ(backend.batch_sizes[r], expected) << "round " << r;
  }
  EXPECT_EQ(stats.batches, kTasks);
  EXPECT_EQ(stats.points, 21u + 20 + 18 + 15 + 11 + 6);
  for (std::thread::id id : backend.threads) EXPECT_EQ(id, std::this_thread::get_id());
}

TEST(SharedBatches, FewerThreadsThanTasksTakeTasksInTurnAndNoneRunsThemOnTheCaller) {
  for (size_t max_threads : {size_t{0}, size_t{1}, size_t{2}}) {
    RecordingBackend backend;
    constexpr size_t kTasks = 5;
    TaskLog log(kTasks);
    const SharedBatchStats stats =
        run_with_shared_batches(backend, kTasks, log.task(3, kTasks), max_threads);
    for (size_t i = 0; i < kTasks; ++i) {
      EXPECT_EQ(log.wrong[i], 0) << "task " << i << ", " << max_threads << " threads";
      EXPECT_EQ(log.calls[i], 3);
      EXPECT_EQ(log.ran_on[i] == std::this_thread::get_id(), max_threads == 0);
    }
    // Batches hold at most max_threads tasks' calls; with none, each call is its own.
    EXPECT_EQ(backend.batch_sizes.size(), max_threads == 0 ? 3 * kTasks : stats.batches);
    if (max_threads > 0) {
      EXPECT_GE(stats.batches, 3 * kTasks / max_threads);
      // Task i has i + 1 points: a batch of m calls has at most the m largest.
      const size_t largest = max_threads * kTasks - max_threads * (max_threads - 1) / 2;
      for (size_t b : backend.batch_sizes) EXPECT_LE(b, largest);
    }
    for (std::thread::id id : backend.threads) EXPECT_EQ(id, std::this_thread::get_id());
  }
}

TEST(SharedBatches, ATasksExceptionReachesTheCallerAndTheOthersFinish) {
  RecordingBackend backend;
  std::atomic<int> finished{0};
  auto run = [&] {
    run_with_shared_batches(
        backend, 4,
        [&](size_t task, const DiffusionBackend& diffusion) {
          const std::vector<glm::dvec3> points = round_points(task, 0);
          std::vector<glm::dvec3> colour(points.size());
          diffusion.diffuse_channels(points, colour, {});
          if (task == 2) throw std::invalid_argument("task 2 failed");
          diffusion.diffuse_channels(points, colour, {});
          ++finished;
        },
        4);
  };
  EXPECT_THROW(run(), std::invalid_argument);
  EXPECT_EQ(finished.load(), 3);
}

TEST(SharedBatches, ABackendErrorReachesTheCallerWithoutALeftWaitingTask) {
  RecordingBackend backend;
  backend.fail_after = 1;  // the second batch throws
  std::atomic<int> finished{0};
  auto run = [&] {
    run_with_shared_batches(
        backend, 3,
        [&](size_t task, const DiffusionBackend& diffusion) {
          for (int round = 0; round < 3; ++round) {
            const std::vector<glm::dvec3> points = round_points(task, round);
            std::vector<glm::dvec3> colour(points.size());
            diffusion.diffuse_channels(points, colour, {});
          }
          ++finished;
        },
        3);
  };
  EXPECT_THROW(run(), std::runtime_error);
  EXPECT_EQ(finished.load(), 0);
  EXPECT_EQ(backend.batch_sizes.size(), 1u);
}

/// This process's address space in bytes (VmSize), or 0 when /proc says nothing.
size_t address_space_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmSize:", 0) == 0) return std::stoull(line.substr(7)) * 1024;  // kB
  return 0;
}

TEST(SharedBatches, WhenThreadsRunOutTheWorkersStartedOrTheCallerRunEveryTask) {
  // In a child process whose address space may grow by 1 MB only, no new thread stack can be
  // mapped, so std::thread throws std::system_error: at once (the tasks then run here), or
  // after the few threads whose stacks glibc kept from earlier tests (they take every task).
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "AddressSanitizer maps its shadow memory under the same address-space limit";
#endif
  std::fflush(nullptr);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    RecordingBackend backend;
    constexpr size_t kTasks = 64;
    TaskLog log(kTasks);
    const size_t used = address_space_bytes();
    const rlimit limit{used + (1u << 20), used + (1u << 20)};
    if (used == 0 || setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
    SharedBatchStats stats;
    try {
      stats = run_with_shared_batches(backend, kTasks, log.task(2, 4), kTasks);
    } catch (...) {
      _exit(4);
    }
    if (stats.workers >= kTasks) _exit(5);
    for (size_t i = 0; i < kTasks; ++i) {
      if (log.wrong[i] != 0 || log.calls[i] != 2) _exit(6);
      if ((log.ran_on[i] == std::this_thread::get_id()) != (stats.workers == 0)) _exit(7);
    }
    _exit(0);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  // 3: no limit could be set; 4: the run threw; 5: every thread started all the same; 6: a
  // task got a wrong value or missed a round; 7: tasks ran on the caller beside workers.
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST(SharedBatches, WrongChannelSizesAreRefusedInTheTask) {
  RecordingBackend backend;
  auto run = [&] {
    run_with_shared_batches(
        backend, 2,
        [&](size_t, const DiffusionBackend& diffusion) {
          const std::vector<glm::dvec3> points(3, glm::dvec3(1.0));
          std::vector<glm::dvec3> colour(2);
          diffusion.diffuse_channels(points, colour, {});
        },
        2);
  };
  EXPECT_THROW(run(), InternalError);
  EXPECT_TRUE(backend.batch_sizes.empty());
}

}  // namespace
}  // namespace cutaway
