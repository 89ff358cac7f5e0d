// Running another program as a child process, without a shell: POV-Ray for renders
// (render/povray_runner.h) and Slurm's sbatch for batch submission (batch/slurm_job.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "base/atomic_file.h"

namespace cutaway {

/// The executable `name` names: `name` itself when it holds a '/', else the first executable
/// file of that name in the folders of $PATH (/usr/local/bin:/usr/bin:/bin when unset).
/// @throws EnvironmentError "'NAME' was not found in PATH; HINT" when there is none
std::string find_executable(const std::string& name, const std::string& hint);

/// A fresh private folder (mode 0700) under the system's temporary folder, named `prefix` and
/// six random characters, where a child process reads and writes its files: removed with
/// everything in it at destruction, and also when SIGTERM, SIGINT or SIGHUP stops the process
/// (RemoveOnSignal).
class TempDir {
 public:
  /// @throws EnvironmentError when it cannot be created
  explicit TempDir(const std::string& prefix);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  RemoveOnSignal guard_;
};

/// The last `count` non-empty lines of `text` (a child's output), joined by newlines, each
/// without trailing spaces and carriage returns: what an error quotes of it.
std::string last_lines(const std::string& text, int count);

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
