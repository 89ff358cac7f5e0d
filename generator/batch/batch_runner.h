// Runs one shard of a batch into an output folder (doc/batch-format.md, Output folder): each
// asset's files written atomically, assets already there with the expected content skipped
// (resuming after a crash or a pre-empted job), the shard's manifest kept current after every
// variant, and the timings in a separate log.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "batch/batch_assets.h"
#include "batch/variant_batch.h"

namespace cutaway {

/// After each variant of the shard: how far the run is.
struct BatchProgress {
  size_t units_done = 0, units = 0;  ///< variants of the shard done (built or skipped), in all
  size_t assets_built = 0, assets_skipped = 0;  ///< so far
  std::string variant;                          ///< the variant just done, TEMPLATE-SEED
  std::vector<std::string> assets;              ///< its assets' stems, in order
  bool skipped = false;                         ///< its assets were all there already
  double seconds = 0;                           ///< the wall time it took
};

/// How run_batch works.
struct BatchRunOptions {
  std::optional<Shard> shard;  ///< none: the whole batch
  BatchBuildOptions build;
  std::function<void(const BatchProgress&)> progress;  ///< may be empty
};

/// What run_batch did.
struct BatchRunResult {
  size_t units = 0;               ///< variants of the shard
  size_t built = 0, skipped = 0;  ///< assets
};

/// Runs the shard `options.shard` of `plan` (of `batch`) into folder `dir` (created when
/// missing):
///  1. writes dir/batch.json (batch_index_text; every shard writes the same bytes);
///  2. reads every manifest in `dir` (manifest*.jsonl): an asset whose record there has the
///     plan's inputs and intact files (record_files_intact) is skipped;
///  3. writes the shard's manifest (manifest_name) with the records of the assets already
///     there, then per variant builds the missing assets (build_batch_unit), writes each file
///     atomically (write_file_atomically) and appends their lines to the manifest (flushed to
///     disk), and appends a line of timings to timings.jsonl / timings-K-of-M.jsonl
///     ({"variant", "skipped", "seconds": {...}}; the only output that differs between runs);
///  4. rewrites the manifest in batch order, so that it depends only on the batch.
/// A crash at any point loses at most the variant in progress: what is on disk is complete
/// files and manifest lines (a line cut short is ignored when read).
/// @throws EnvironmentError when a file cannot be written; InputError when a template
///         cannot be read
BatchRunResult run_batch(const Batch& batch, const BatchPlan& plan,
                         const std::filesystem::path& dir, const BatchRunOptions& options);

}  // namespace cutaway
