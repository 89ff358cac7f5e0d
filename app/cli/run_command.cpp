// How every subcommand runs (commands.h, run_command): outputs checked and committed together,
// --stats printed, errors turned into messages and exit codes (doc/command-line.md).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/hash.h"

namespace cutaway::cli {

namespace {

/// Refuses an output option given an empty path (`-o ""`), which would otherwise read as
/// "not given" (and, for `model`, write NAME.glb).
/// @throws OutputPathError "OPTION: the path is empty"
void refuse_empty_output_paths(const CLI::App& command) {
  for (const char* name : {"-o", "--png", "--render"}) {
    const CLI::Option* option = command.get_option_no_throw(name);
    if (option == nullptr) continue;
    for (const std::string& value : option->results())
      if (value.empty()) throw OutputPathError(std::string(name) + ": the path is empty");
  }
}

/// Prints `--stats`: the subcommand's `stats` (empty for those without counts of their own) and
/// "outputs_fnv1a64", each file in `written` (relative to the working directory when it lies
/// under it, else absolute: never "../../tmp/x") with the FNV-1a 64-bit hash of its bytes as
/// 16 hex digits: what a golden test compares across machines. One line of JSON on stderr.
void print_stats_line(nlohmann::ordered_json stats,
                      const std::vector<std::filesystem::path>& written) {
  nlohmann::ordered_json files = nlohmann::ordered_json::object();
  const std::filesystem::path here = std::filesystem::current_path();
  for (const std::filesystem::path& f : written) {
    const std::filesystem::path relative = f.lexically_proximate(here);
    const bool under = !relative.empty() && *relative.begin() != "..";
    files[(under ? relative : std::filesystem::absolute(f).lexically_normal()).string()] =
        hex64(fnv1a64(read_file_bytes(f)));
  }
  stats["outputs_fnv1a64"] = std::move(files);
  std::fprintf(stderr, "%s\n", stats.dump().c_str());
}

}  // namespace

int run_command(const Command& command, const Common& common_options, bool stats) {
  // Every file a command writes goes through `outputs`: registered and checked before any
  // work, committed (renamed into place together) only when the command succeeds.
  OutputSet outputs;
  nlohmann::ordered_json stats_json = nlohmann::ordered_json::object();
  Common common = common_options;
  common.stats = stats ? &stats_json : nullptr;
  try {
    refuse_empty_output_paths(*command.app);
    const int code = command.run(common, outputs);
    if (code == 0) {
      outputs.commit();
      if (stats) print_stats_line(stats_json, outputs.committed());
    }
    return code;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "cutaway: %s\n", e.what());
    return 2;
  } catch (const OutputPathError& e) {
    std::fprintf(stderr, "cutaway: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    // A writer's error names its staging path; describe() names the user's file instead.
    std::fprintf(stderr, "cutaway: error: %s\n", outputs.describe(e.what()).c_str());
    return 1;
  }
}

}  // namespace cutaway::cli
