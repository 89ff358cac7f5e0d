#include "diffusion/shared_batches.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include "base/error.h"

namespace cutaway {

namespace {

/// What the tasks and the serving thread share, under `mutex`.
struct Exchange {
  /// One task's pending call.
  struct Call {
    bool waiting = false;  ///< asked, not yet served
    std::span<const glm::dvec3> points;
    std::span<glm::dvec3> colour;
    std::span<glm::dvec2> material;
  };

  std::mutex mutex;
  std::condition_variable served;  ///< a batch was diffused (or failed)
  std::condition_variable idle;    ///< no task is running: all wait or have finished
  std::vector<Call> calls;         ///< per task
  size_t running = 0;              ///< workers neither waiting nor out of tasks
  bool failed = false;             ///< the backend threw: waiting calls throw too
};

/// The backend as one task sees it.
class TaskDiffusion final : public DiffusionBackend {
 public:
  TaskDiffusion(const DiffusionBackend& backend, Exchange& exchange, size_t task)
      : backend_(backend), exchange_(exchange), task_(task) {}

  void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                        std::span<glm::dvec2> material) const override {
    check_channel_sizes(points.size(), colour.size(), material.size());
    if (points.empty()) return;
    std::unique_lock lock(exchange_.mutex);
    Exchange::Call& call = exchange_.calls[task_];
    call = {true, points, colour, material};
    if (--exchange_.running == 0) exchange_.idle.notify_one();
    exchange_.served.wait(lock, [&] { return !call.waiting || exchange_.failed; });
    if (call.waiting) throw InternalError("diffusion: the shared batch failed");
  }
  std::string name() const override { return backend_.name(); }
  size_t rays_cast() const override { return backend_.rays_cast(); }
  int threads() const override { return backend_.threads(); }

 private:
  const DiffusionBackend& backend_;
  Exchange& exchange_;
  size_t task_;
};

}  // namespace

SharedBatchStats run_with_shared_batches(
    const DiffusionBackend& backend, size_t count,
    const std::function<void(size_t, const DiffusionBackend&)>& task, size_t max_threads) {
  SharedBatchStats stats;
  Exchange exchange;
  exchange.calls.resize(count);
  std::vector<std::exception_ptr> errors(count);
  std::atomic<size_t> next{0};  // the next task a worker takes
  auto run_tasks = [&] {
    for (size_t i = next++; i < count; i = next++) {
      try {
        task(i, TaskDiffusion(backend, exchange, i));
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
    std::lock_guard lock(exchange.mutex);
    if (--exchange.running == 0) exchange.idle.notify_one();
  };
  const size_t workers = std::min(count, max_threads);
  exchange.running = workers;
  std::vector<std::thread> threads;
  threads.reserve(workers);
  try {
    while (threads.size() < workers) threads.emplace_back(run_tasks);
  } catch (const std::system_error&) {
    // No more threads to be had: the workers started take every task.
    std::lock_guard lock(exchange.mutex);
    exchange.running -= workers - threads.size();
  }
  stats.workers = threads.size();
  std::exception_ptr backend_error;
  {
    std::unique_lock lock(exchange.mutex);
    while (true) {
      exchange.idle.wait(lock, [&] { return exchange.running == 0; });
      std::vector<size_t> waiting;
      for (size_t i = 0; i < count; ++i)
        if (exchange.calls[i].waiting) waiting.push_back(i);
      if (waiting.empty()) break;  // every task has finished
      // One batch, in task order; the tasks are blocked, so their spans stay valid.
      bool with_material = false;
      size_t total = 0;
      for (size_t i : waiting) {
        with_material = with_material || !exchange.calls[i].material.empty();
        total += exchange.calls[i].points.size();
      }
      std::vector<glm::dvec3> points, colour(total);
      std::vector<glm::dvec2> material(with_material ? total : 0);
      points.reserve(total);
      for (size_t i : waiting)
        points.insert(points.end(), exchange.calls[i].points.begin(),
                      exchange.calls[i].points.end());
      lock.unlock();
      const auto start = std::chrono::steady_clock::now();
      try {
        backend.diffuse_channels(points, colour, material);
      } catch (...) {
        backend_error = std::current_exception();
      }
      stats.seconds_diffuse +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++stats.batches;
      stats.points += total;
      lock.lock();
      if (backend_error) {
        exchange.failed = true;
        exchange.running = waiting.size();
        exchange.served.notify_all();
        exchange.idle.wait(lock, [&] { return exchange.running == 0; });
        break;
      }
      size_t next = 0;
      for (size_t i : waiting) {
        Exchange::Call& call = exchange.calls[i];
        for (size_t k = 0; k < call.points.size(); ++k, ++next) {
          call.colour[k] = colour[next];
          if (!call.material.empty()) call.material[k] = material[next];
        }
        call.waiting = false;
      }
      exchange.running = waiting.size();
      exchange.served.notify_all();
    }
  }
  for (std::thread& t : threads) t.join();
  if (backend_error) std::rethrow_exception(backend_error);
  // Without a worker, the tasks run here, one at a time, calling the backend directly.
  for (size_t i = next++; i < count; i = next++) {
    try {
      task(i, backend);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return stats;
}

}  // namespace cutaway
