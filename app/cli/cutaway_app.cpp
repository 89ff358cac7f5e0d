// The `cutaway` app as CLI11 holds it: the common options and every subcommand registered (one
// NAME_command.cpp each), nothing parsed or run (main.cpp does that; tests walk the options).
#include <vector>

#include <CLI/CLI.hpp>

#include "app/cli/commands.h"

namespace cutaway::cli {

std::vector<Command> add_cutaway_commands(CLI::App& app, CommonOptions& options) {
  app.description("cutaway: cut objects with a consistent interior, from diffusion surfaces "
                  "(Takayama et al. 2010)");
  app.require_subcommand(1);
  app.set_version_flag("--version", "cutaway " CUTAWAY_VERSION);
  app.fallthrough();  // common options may follow the subcommand
  add_common_options(app, options);
  return {add_model_command(app), add_section_command(app), add_variants_command(app),
          add_piece_command(app), add_sheet_command(app),   add_scene_command(app),
          add_batch_command(app), add_volume_command(app),  add_check_command(app),
          add_edit_command(app)};
}

}  // namespace cutaway::cli
