// Running another program as a child process, without a shell: POV-Ray for renders
// (render/povray_runner.h) and Slurm's sbatch for batch submission (batch/slurm_job.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cutaway {

/// The executable `name` names: `name` itself when it holds a '/', else the first executable
/// file of that name in the folders of $PATH (/usr/local/bin:/usr/bin:/bin when unset).
/// @throws EnvironmentError "'NAME' was not found in PATH; HINT" when there is none
std::string find_executable(const std::string& name, const std::string& hint);

/// How a child process ended, and what it printed.
struct ChildResult {
  int status = 0;      ///< as waitpid() reports it (WIFEXITED, WEXITSTATUS, WIFSIGNALED)
  std::string output;  ///< stdout and stderr interleaved; the last 256 KiB when it printed more
};

/// Runs the executable `exe` (a path, e.g. from find_executable) with `args` (args[0] is the
/// program's name) in folder `dir` and waits for its end: fork + chdir + execv, stdin from
/// /dev/null, stdout and stderr captured into one pipe. The child gets SIGTERM when the calling
/// thread ends (PR_SET_PDEATHSIG: call it from a thread that outlives the child, e.g. the main
/// thread), and SIGKILL when SIGTERM, SIGINT or SIGHUP stops this process (RemoveOnSignal).
/// @throws EnvironmentError "cannot start EXE: REASON" when it cannot be started, and when a
///         pipe or the fork fails
ChildResult run_child(const std::filesystem::path& dir, const std::string& exe,
                      const std::vector<std::string>& args);

}  // namespace cutaway
