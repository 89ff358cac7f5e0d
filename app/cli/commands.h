// The `cutaway` subcommands, one source file each (NAME_command.cpp) that registers its
// options and calls the libraries, and what they share; main.cpp registers them, parses the
// arguments and runs the chosen one (run_command).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/cli/options.h"
#include "base/atomic_file.h"
#include "cache/cut_cache.h"
#include "cut/object_cut.h"
#include "model/ds_model.h"
#include "model/template.h"
#include "pieces/cut_spec.h"
#include "pieces/pieces.h"
#include "variation/variation.h"

namespace cutaway::cli {

// Outputs: every subcommand registers each file it will write in the OutputSet run_command
// owns, before any work, writes to the path add() returns, and run_command commits the set
// when the subcommand returns 0 (atomic_file.h; a refused path is OutputPathError, exit code 2).

/// Options common to all subcommands.
struct Common {
  std::string backend = "auto";  ///< auto | cpu | gl
  int threads = 0;               ///< 0: all cores
  /// `--stats`: where a subcommand puts its JSON counts and "seconds" per stage (keys in the
  /// order given); null without --stats. run_command prints it as one line on stderr once the
  /// outputs are committed, with "outputs_fnv1a64" added (each written file's content hash).
  nlohmann::ordered_json* stats = nullptr;
  CapSampling sampling = CapSampling::Adaptive;  ///< --sampling: which cap points are diffused
  bool adaptive_directions = true;               ///< --directions adaptive (true) or every (false)
  bool quiet = false;                            ///< --quiet: errors only (no progress bars)
};

/// A subcommand's work, bound to its parsed arguments: returns the exit code.
/// @throws InputError, UsageError, OutputPathError (bad input: exit code 2); anything else is
///         a failure (exit code 1)
using CommandRun = std::function<int(const Common& common, OutputSet& outputs)>;

/// One registered subcommand: its CLI11 app (true when chosen) and its work.
struct Command {
  CLI::App* app = nullptr;
  CommandRun run;
};

// Each NAME_command.cpp registers its subcommand, options and their rules on `app` (the
// `cutaway` app), and returns it with the work that calls the libraries once it is chosen.

/// `cutaway model TEMPLATE [-o model.glb] [--png view.png] [--size PX] [--seed S]`.
Command add_model_command(CLI::App& app);
/// `cutaway section TEMPLATE --plane SPEC [-o cut.glb|cut.ply] [--png cut.png] [--cube N]
/// [--seed S]`.
Command add_section_command(CLI::App& app);
/// `cutaway variants TEMPLATE --count N [--seed S] -o DIR [--shard K/M] [--sheet N] [--tile PX]`.
Command add_variants_command(CLI::App& app);
/// `cutaway piece TEMPLATE --cut SPEC [--seed S] [-o pieces.glb|.gltf|.pov] [--png p.png]`.
Command add_piece_command(CLI::App& app);
/// `cutaway sheet TEMPLATE[:CUT][@VIEW]... -o sheet.png [--cut SPEC] [--tile PX] [--columns N]`.
Command add_sheet_command(CLI::App& app);
/// `cutaway scene SCENE [--seed S] -o OUT.glb|.gltf|.pov [-o ...] [--png preview.png]
/// [--render out.png]`.
Command add_scene_command(CLI::App& app);
/// `cutaway batch BATCH.yaml -o DIR [--shard K/M] [--slurm ...]` and `cutaway batch merge DIR`.
Command add_batch_command(CLI::App& app);
/// `cutaway volume TEMPLATE -o OUT [-o ...] [--seed S] [--voxel LENGTH]`.
Command add_volume_command(CLI::App& app);
/// `cutaway check FILE...`.
Command add_check_command(CLI::App& app);
/// `cutaway edit [TEMPLATE] [--port N]`.
Command add_edit_command(CLI::App& app);

/// Makes `app` the `cutaway` command line: its description, --version, the common options
/// (stored into `options` when parsed) and every subcommand above, registered but not parsed
/// or run; main() parses the arguments and runs the chosen one (run_command).
/// @returns the subcommands, in the order of `cutaway --help`
std::vector<Command> add_cutaway_commands(CLI::App& app, CommonOptions& options);

/// Runs the chosen `command` as every subcommand runs (app/cli/run_command.cpp): its output
/// paths checked, its outputs committed when it returns 0, `--stats` printed, and each error
/// turned into its message on stderr and its exit code (2 bad input, 1 failure).
/// @param stats  whether --stats was given
int run_command(const Command& command, const Common& common, bool stats);

/// `text` (the `--cut` notation) for `tmpl`, refused when it is malformed or would make more
/// than kMaxPiecesPerCut pieces.
/// @throws UsageError "WHAT: rule" (`what` names the cut for the user)
CutSpec checked_cut(const Template& tmpl, const std::string& text, const std::string& what);

/// The diffusion backend --backend chooses, with cube-map size `cube`, --threads and
/// --directions.
DiffusionFactory diffusion_factory(int cube, const Common& common);

/// The backend --backend picks on this machine: "cpu" or "gl" (DiffusionBackend::name); with
/// --backend auto it probes for a GPU (a context made and dropped, about 0.1 s).
std::string resolved_backend(const Common& common);

/// `common` with its backend resolved (resolved_backend), so that the calls that follow
/// (diffusion_factory, diffusion_settings, resolved_backend) do not probe again.
Common with_resolved_backend(const Common& common);

/// What of the backend diffusion_factory(cube, common) makes changes colours, as cut cache keys
/// name it: "backend=KIND cube=N directions=D", KIND what --backend picks on this machine.
std::string diffusion_settings(int cube, const Common& common);

/// The cut cache `args` ask for, its warnings logged; null with --no-cache, or (logged) when
/// no folder is given and neither XDG_CACHE_HOME nor HOME is set.
std::unique_ptr<CutCache> open_cut_cache(const CacheArgs& args);

/// The `cut_cache` of `--stats`: hits, misses, stored, damaged and evicted entries of `cache`
/// this run (null without a cache). A run that cut every object afresh has no hits.
nlohmann::ordered_json cut_cache_stats(const CutCache* cache);

/// `variant` cut for a picture of its pieces (`piece`, `sheet`): every piece kept, colours
/// (vertex colours, or with CapColours::Texture cut faces and skin baked into textures, the
/// skin's patterns per texel) modulated by the template's Perlin bands with strength `perlin`
/// and `seed` in the object frame, the template's materials added to `assets`, the backend
/// --backend chooses with cube-map size `cube` (cut_object).
/// @throws UsageError "WHAT: rule" when the cut misses the object (`what` names the cut)
CutObject cut_for_view(SceneAssets& assets, const Variant& variant, const CutSpec& cut, int cube,
                       const Common& common, double perlin, uint64_t seed, const std::string& what,
                       CapColours colours);

/// The exit code of `batch merge` when shards are still missing: not bad input (2) nor a
/// failure (1), but more work due.
inline constexpr int kExitBatchIncomplete = 3;

}  // namespace cutaway::cli
