// Batches on a Slurm cluster (doc/batch-format.md, Slurm): an sbatch array script whose task
// K of M runs `cutaway batch BATCH -o DIR --shard K/M`, and its submission with sbatch.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "base/outcome.h"

namespace cutaway {

/// One array job of a batch.
struct SlurmJob {
  std::string cutaway;     ///< absolute path of the cutaway executable (on the shared filesystem)
  std::string batch_file;  ///< absolute path of the batch file
  std::string dir;         ///< absolute path of the output folder
  std::string job_name;    ///< the batch's name: the job is "cutaway-NAME"
  int array = 4;           ///< array tasks = shards, 1..kMaxShards
  int cpus_per_task = 1;   ///< each task's --threads
  std::string partition;   ///< empty: the cluster's default
  std::string time;        ///< Slurm's --time (e.g. "2:00:00"); empty: the partition's default
  std::vector<std::string> extra_args;  ///< passed on to every task (e.g. --backend cpu)
};

/// Passes when `job` can become a script; else fails with why not: a path with white space, a
/// quote, '%' or a newline (sbatch's #SBATCH lines take no quoting), a partition or time
/// outside [A-Za-z0-9_.,:-], array outside 1..100000, cpus_per_task outside 1..1024.
Check check_slurm_job(const SlurmJob& job);

/// The sbatch script of `job`: #SBATCH lines (job name, --array=1-M, --cpus-per-task, task
/// output to DIR/slurm/%A_%a.out, partition and time when given), then `exec` of cutaway
/// with every argument single-quoted and --shard "$SLURM_ARRAY_TASK_ID/M".
/// @pre check_slurm_job(job) passes
std::string sbatch_script(const SlurmJob& job);

/// Submits the script at `script` with `sbatch --parsable` (found in PATH) and returns the job
/// id it prints.
/// @throws EnvironmentError when sbatch is missing, fails (its message quoted) or prints no
///         job id
std::string submit_sbatch(const std::filesystem::path& script);

}  // namespace cutaway
