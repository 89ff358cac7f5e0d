// What the subcommands' options share: the usage error, the rules CLI11 checks values with,
// the export options of the commands that write scenes, the style of those that draw pictures,
// and the options common to all.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <CLI/CLI.hpp>

#include "scene/scene.h"

namespace cutaway::cli {

/// A bad command-line argument: reported like InputError, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws UsageError "OPTION: 'PATH' must end in EXT" unless `path` ends in `ext` (".glb").
void require_extension(const std::string& option, const std::string& path, const char* ext);

/// The rule of a numeric option, for every numeric option of every subcommand: the text must be
/// a decimal number (parse_decimal: digits, point, exponent; no nan, inf or hex) from `min` to
/// `max`, and whole when `whole`. CLI11's own Range lets NaN through (every comparison with it
/// is false); this rule refuses it while the arguments are parsed, before any work.
/// @returns a CLI11 check that fails with 'must be a [whole] number from MIN to MAX, not "TEXT"'
///          (CLI11 prefixes the option: exit code 2 with "OPTION: rule")
CLI::Validator number_rule(double min, double max, bool whole);

/// number_rule for an option of type T: whole numbers for an integer T.
template <class T>
CLI::Validator number_rule(T min, T max) {
  return number_rule(static_cast<double>(min), static_cast<double>(max), std::is_integral_v<T>);
}

/// The rule of a numeric option with no upper bound of its own (a length whose limits follow
/// from the input): a decimal number (as number_rule) above 0.
/// @returns a CLI11 check that fails with 'must be a number above 0, not "TEXT"'
CLI::Validator positive_number_rule();

/// --seed's rule (parse_seed), checked on the text before CLI11 converts it, which would
/// saturate a seed beyond 2^63 - 1 silently.
const CLI::Validator& seed_rule();

/// --shard's rule (parse_shard), so that an empty value is refused rather than read as "not
/// given" (which would build the whole batch).
const CLI::Validator& shard_rule();

/// `--compress none|quantize|meshopt`, `--lods N`, `--textures jpeg|png|ktx2` and
/// `--texture-fallback` of the commands
/// that write glTF and POV-Ray scenes, into the given variables.
void add_export_options(CLI::App* command, std::string& compress, int& lods, std::string& textures,
                        bool& texture_fallback);

/// `--for godot|unreal|unity|web|blender` (kEngineProfiles, engine_profile.h) into `engine`,
/// described by `description` (what the profile sets for this command).
void add_engine_option(CLI::App* command, std::string& engine, const std::string& description);

/// The Basis Universal encoder KTX2 textures need (find_basisu, ktx2_texture.h).
/// @throws UsageError "WHAT: ..." (exit code 2) saying how to install it when there is none
std::filesystem::path require_basisu(const std::string& what);

/// `--colours texture|vertex` of the commands that cut objects for files (scene, piece): cut
/// faces and swept skins baked into textures (with the skin patterns and their relief per
/// texel) or left in vertex colours; into `colours`.
void add_colours_option(CLI::App* command, std::string& colours);

/// `--style` and `--silhouettes` of the commands that draw pictures (scene, piece, sheet).
struct StyleArgs {
  std::string style;                  ///< "realistic", "illustration", or empty: not given
  std::optional<double> silhouettes;  ///< not given: the style's default
};

/// Adds `--style realistic|illustration` and `--silhouettes S` (0..10) to `command`, into
/// `args`. `what` names where the strokes go, for the help text.
void add_style_options(CLI::App* command, StyleArgs& args, const std::string& what);

/// The silhouette stroke strength `args` ask for: --silhouettes when given, else the style's
/// default (default_silhouettes: 0 realistic, 1 illustration), the style being --style when
/// given, else `fallback` (a scene file's own).
double stroke_strength(const StyleArgs& args, RenderStyle fallback = RenderStyle::Realistic);

/// `--cache DIR`, `--no-cache`, `--cache-size SIZE` and `--cache-shared` of the commands that cut
/// objects through the cut cache (scene, batch).
struct CacheArgs {
  std::string dir;         ///< empty: CutCache::default_dir()
  bool off = false;        ///< --no-cache
  uint64_t max_bytes = 0;  ///< --cache-size in bytes (0: kDefaultCutCacheBytes)
  bool shared = false;     ///< --cache-shared: a folder other users may write is accepted
};

/// Adds the cache options to `command`, stored into `args` when parsed.
void add_cache_options(CLI::App* command, CacheArgs& args);

/// The options every subcommand takes, before or after its name (`cutaway --stats scene ...`
/// or `cutaway scene ... --stats`).
struct CommonOptions {
  bool stats = false, quiet = false, verbose = false;
  int threads = 0;                      ///< 0: all cores
  std::string backend = "auto";         ///< auto | cpu | gl
  std::string sampling = "adaptive";    ///< dense: every vertex, for comparison
  std::string directions = "adaptive";  ///< every: every cube texel, for comparison
};

/// Adds the common options to `app`, stored into `options` when parsed.
void add_common_options(CLI::App& app, CommonOptions& options);

}  // namespace cutaway::cli
