// The `cutaway` command line: builds the app (cutaway_app.cpp), parses the arguments and runs
// the chosen subcommand; nothing else lives here (doc/architecture.md, Style).
// Exit codes: 0 success, 2 bad input, 1 internal failure, 3 an incomplete batch.
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>
#include <oneapi/tbb/global_control.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "app/cli/commands.h"

int main(int argc, char** argv) {
  using namespace cutaway::cli;
  CLI::App app;
  CommonOptions options;
  const std::vector<Command> commands = add_cutaway_commands(app, options);

  spdlog::set_default_logger(spdlog::stderr_color_st("cutaway"));
  spdlog::set_pattern("%v");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  spdlog::set_level(options.quiet ? spdlog::level::err
                                  : (options.verbose ? spdlog::level::debug : spdlog::level::info));
  // --threads bounds every stage that shares its work out over the cores, not only PMVC's.
  std::optional<oneapi::tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(oneapi::tbb::global_control::max_allowed_parallelism, options.threads);
  const Common common{options.backend,
                      options.threads,
                      nullptr,
                      options.sampling == "adaptive" ? cutaway::CapSampling::Adaptive
                                                     : cutaway::CapSampling::Dense,
                      options.directions == "adaptive",
                      options.quiet};
  for (const Command& command : commands)
    if (*command.app) return run_command(command, common, options.stats);
  return 0;
}
