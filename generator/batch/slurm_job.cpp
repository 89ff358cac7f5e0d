#include "batch/slurm_job.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include <sys/wait.h>

#include "base/child_process.h"
#include "base/error.h"
#include "batch/variant_batch.h"

namespace cutaway {

namespace {

/// `text` in single quotes for the shell (a quote inside becomes '\'').
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool plain_value(const std::string& text) {
  return std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '.' || c == ',' || c == ':' || c == '-';
  });
}

/// Whether `path` can stand unquoted in an #SBATCH line: valid UTF-8 with no white space of
/// any kind (sbatch splits its lines on space, tab, vertical tab, form feed, CR and LF), no
/// other control character (C0, DEL, C1), no quote, backslash or '%' (a filename pattern).
bool sbatch_safe_path(const std::string& path) {
  for (size_t i = 0; i < path.size();) {
    const size_t n = utf8_length(path, i);
    if (n == 0) return false;
    const unsigned char c = static_cast<unsigned char>(path[i]);
    if (n == 1 && (c <= 0x20 || c == 0x7f || c == '\'' || c == '"' || c == '%' || c == '\\'))
      return false;
    // C1 controls U+0080..U+009F are 0xC2 0x80..0x9F; U+0085 (NEL) and U+00A0 are white space
    // to some splitters too.
    if (n == 2 && c == 0xc2 && static_cast<unsigned char>(path[i + 1]) <= 0xa0) return false;
    i += n;
  }
  return true;
}

}  // namespace

Check check_slurm_job(const SlurmJob& job) {
  for (const std::string* path : {&job.cutaway, &job.batch_file, &job.dir}) {
    if (!sbatch_safe_path(*path))
      return Check::none(
          "the path " + quoted(*path) +
          " holds white space, a control character, a quote, a backslash, '%' or bytes "
          "that are not UTF-8 (sbatch splits and expands #SBATCH lines on them): choose "
          "another folder");
  }
  if (!plain_value(job.partition))
    return Check::none("--partition must hold only A-Z a-z 0-9 _ . , : -");
  if (!plain_value(job.time)) return Check::none("--time must hold only A-Z a-z 0-9 _ . , : -");
  if (job.array < 1 || job.array > kMaxShards)
    return Check::none("--array must be from 1 to " + std::to_string(kMaxShards));
  if (job.cpus_per_task < 1 || job.cpus_per_task > 1024)
    return Check::none("the CPUs per task must be from 1 to 1024");
  return {};
}

std::string sbatch_script(const SlurmJob& job) {
  const std::string m = std::to_string(job.array);
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# cutaway batch " << job.job_name << ": " << m << " array tasks, task K writing shard K/"
    << m << " of the batch.\n"
    << "# Written by `cutaway batch --slurm`; `cutaway batch merge " << job.dir
    << "` checks and merges the shards when the job is done.\n"
    << "#SBATCH --job-name=cutaway-" << job.job_name << "\n"
    << "#SBATCH --array=1-" << m << "\n"
    << "#SBATCH --ntasks=1\n"
    << "#SBATCH --cpus-per-task=" << job.cpus_per_task << "\n"
    << "#SBATCH --output=" << job.dir << "/slurm/%A_%a.out\n";
  if (!job.partition.empty()) s << "#SBATCH --partition=" << job.partition << "\n";
  if (!job.time.empty()) s << "#SBATCH --time=" << job.time << "\n";
  s << "set -euo pipefail\n"
    << "exec " << shell_quoted(job.cutaway) << " batch " << shell_quoted(job.batch_file) << " -o "
    << shell_quoted(job.dir) << " --shard \"${SLURM_ARRAY_TASK_ID}/" << m << "\" --threads "
    << job.cpus_per_task;
  for (const std::string& arg : job.extra_args) s << " " << shell_quoted(arg);
  s << "\n";
  return s.str();
}

std::string submit_sbatch(const std::filesystem::path& script) {
  const std::string exe = find_executable(
      "sbatch", "run this on a Slurm login node (Debian: the slurm-client package)");
  const ChildResult run =
      run_child(std::filesystem::current_path(), exe, {"sbatch", "--parsable", script.string()});
  if (!WIFEXITED(run.status) || WEXITSTATUS(run.status) != 0)
    throw EnvironmentError("sbatch failed on " + script.string() + ": " + run.output);
  // --parsable prints "JOBID" or "JOBID;CLUSTER" on its last line (warnings may come first).
  std::istringstream in(run.output);
  std::string line, id;
  while (std::getline(in, line)) {
    const std::string first = line.substr(0, line.find(';'));
    if (!first.empty() && std::all_of(first.begin(), first.end(), ::isdigit)) id = first;
  }
  if (id.empty()) throw EnvironmentError("sbatch printed no job id: " + run.output);
  return id;
}

}  // namespace cutaway
