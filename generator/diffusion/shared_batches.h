// Shared diffusion batches: several samplers (one per cap) run at once, each on its own thread,
// and the points they ask to diffuse in small rounds are diffused together, in one call of the
// backend on the calling thread. Adaptive sampling diffuses a cap in rounds of tens of points;
// one cap at a time, a round cannot keep many cores (or a GPU) busy, and the cap's meshing and
// interpolation run on one core. Results are those of one cap at a time: a backend's value at
// a point does not depend on the batch it is diffused in (DiffusionBackend).
#pragma once

#include <cstddef>
#include <functional>

#include "diffusion/diffusion.h"

namespace cutaway {

/// Counts of one run_with_shared_batches call.
struct SharedBatchStats {
  size_t batches = 0;          ///< calls of the backend
  size_t points = 0;           ///< points diffused in them
  double seconds_diffuse = 0;  ///< wall time spent in the backend's calls
  size_t workers = 0;          ///< worker threads started (fewer than asked for when the system has
                               ///< no more to give)
};

/// Runs task(i, diffusion) for every i in [0, count) on up to `max_threads` worker threads
/// (each takes the next task when it finishes one), where `diffusion` stands for `backend`: a
/// task's diffuse_channels call waits until every task still running waits for one too (or its
/// worker has run out of tasks), and then the points of all waiting calls, in task order, are
/// diffused in one call of `backend` on the thread that called this function (an OpenGL
/// backend's context stays on its thread). Material channels are computed for the whole batch
/// when any call asks for them. With no worker thread (max_threads 0, or none to be had) the
/// tasks run on the calling thread, one at a time, with `backend` itself. Returns when every
/// task has finished.
/// @throws the exception of the lowest-numbered task that threw; an exception of `backend`
///         (the tasks still waiting then throw InternalError and are not reported)
SharedBatchStats run_with_shared_batches(
    const DiffusionBackend& backend, size_t count,
    const std::function<void(size_t, const DiffusionBackend&)>& task, size_t max_threads);

}  // namespace cutaway
