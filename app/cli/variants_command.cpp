// `cutaway variants`: seeded variants of one template (DS models as glb), their manifest and a
// contact sheet of their mid-height cuts.
#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <unistd.h>

#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "app/cli/progress_bar.h"
#include "base/atomic_file.h"
#include "batch/variant_batch.h"
#include "batch/variant_set.h"
#include "io/template_parser.h"
#include "io/text_rules.h"
#include "render/image/contact_sheet.h"
#include "render/image/image.h"
#include "scene/scene.h"
#include "variation/variation.h"

namespace cutaway::cli {

namespace {

/// `cutaway variants TEMPLATE --count N [--seed S] -o DIR [--shard K/M] [--sheet N] [--tile PX]`
///.
struct VariantsArgs {
  std::string template_path;
  std::string output_dir;
  int count = 1;
  uint64_t seed = 0;
  std::string shard;  ///< "K/M" when shard_given
  bool shard_given = false;
  int sheet = 64;  ///< contact sheet: at most this many tiles (0: no sheet)
  int tile = 256;  ///< contact-sheet tile size, pixels
};

int run_variants(const VariantsArgs& a, const Common& common, OutputSet& outputs) {
  Shard shard;
  if (a.shard_given) {
    const Outcome<Shard> parsed = parse_shard(a.shard);
    if (!parsed) throw UsageError("--shard: " + parsed.reason());
    shard = *parsed;
  }
  // The last seed must be one --seed accepts, so that every file's seed can be given again.
  if (a.seed > kMaxSeed - static_cast<uint64_t>(a.count - 1)) {
    throw UsageError("--seed " + std::to_string(a.seed) + " with --count " +
                     std::to_string(a.count) + " goes beyond the largest seed, " +
                     std::to_string(kMaxSeed) + ": give --seed at most " +
                     std::to_string(kMaxSeed - static_cast<uint64_t>(a.count - 1)));
  }
  // The contact sheet's pixels, at most: one tile-wide square per variant on it.
  const long long sheet_pixels =
      static_cast<long long>(std::min(a.sheet, a.count)) * a.tile * a.tile;
  if (sheet_pixels > kMaxRenderPixels)
    throw UsageError("--sheet " + std::to_string(a.sheet) + " with --tile " +
                     std::to_string(a.tile) + " makes a contact sheet of up to " +
                     std::to_string(sheet_pixels) + " pixels (at most " +
                     std::to_string(kMaxRenderPixels) + "): fewer tiles or a smaller --tile");
  const Template tmpl = load_template(a.template_path);
  const std::filesystem::path dir(a.output_dir);
  const int first = shard.begin(a.count), last = shard.end(a.count);
  // Every file is registered (and DIR created) before the first variant is built.
  std::map<std::string, std::filesystem::path> glb_files;
  for (int i = first; i < last; ++i) {
    const std::string file = variant_file_name(tmpl.name, a.seed + static_cast<uint64_t>(i));
    glb_files[file] = outputs.add("-o", (dir / file).string());
  }
  const std::filesystem::path manifest_file = outputs.add("-o", (dir / "manifest.json").string());
  const std::filesystem::path sheet_file =
      a.sheet > 0 ? outputs.add("-o", (dir / "contact-sheet.png").string())
                  : std::filesystem::path();
  const ProgressBar progress("variants", last - first, !common.quiet && isatty(fileno(stderr)));
  progress.show(0);
  const std::vector<VariantRecord> records = build_variant_models(
      tmpl, a.seed, first, last,
      [&](const std::string& file, const std::string& glb) {
        write_file_atomically(glb_files.at(file), glb);
        spdlog::debug("wrote {}", (dir / file).string());
      },
      [&](int done) { progress.show(done); });
  write_file_atomically(
      manifest_file,
      variant_manifest(tmpl.name, a.shard_given ? std::optional(shard) : std::nullopt, records));
  // The contact sheet comes last (all files are committed together, or none); its variants
  // are built again (same seed, same model) rather than all kept.
  std::vector<Outcome<CrossSection>> sections;
  bool any = false;
  const DiffusionFactory sheet_diffusion = diffusion_factory(8, common);
  for (int i = first; i < std::min(last, first + a.sheet); ++i) {
    const uint64_t seed = a.seed + static_cast<uint64_t>(i);
    sections.push_back(variant_section(make_variant(tmpl, seed), sheet_diffusion));
    if (sections.back()) any = true;
    else
      spdlog::warn("seed {}: no horizontal section at mid-height ({}); its tile stays empty", seed,
                   sections.back().reason());
  }
  if (any) {
    SectionTileOptions tile_options;
    tile_options.tile_px = a.tile;
    write_png(sheet_file, section_sheet(std::move(sections), tile_options));
  }
  spdlog::info("wrote {} variant(s) of {}, manifest.json{} to {}", last - first, tmpl.name,
               any ? ", contact-sheet.png" : "", dir.string());
  return 0;
}

}  // namespace

Command add_variants_command(CLI::App& app) {
  auto args = std::make_shared<VariantsArgs>();
  CLI::App* variants = app.add_subcommand(
      "variants", "random variants of a template (glb + manifest.json + contact-sheet.png)");
  variants->add_option("TEMPLATE", args->template_path, "template file (.yaml)")->required();
  variants->add_option("--count", args->count, "number of variants")->check(number_rule(1, 100000));
  variants->add_option("--seed", args->seed, "seed of the first variant (then seed + 1, ...)")
      ->check(seed_rule());
  variants->add_option("-o,--output", args->output_dir, "output folder")->required();
  variants
      ->add_option("--shard", args->shard,
                   "K/M: write only the K-th of M contiguous shares of the variants (seeds "
                   "unchanged, so the shards together make one unsharded run)")
      ->check(shard_rule());
  variants
      ->add_option("--sheet", args->sheet,
                   "contact-sheet.png: the mid-height horizontal cuts of the first N "
                   "variants (of the shard) at one scale; 0: none")
      ->check(number_rule(0, 256));
  variants
      ->add_option("--tile", args->tile,
                   "contact-sheet tile size in pixels (the largest cut's extent)")
      ->check(number_rule(16, 4096));
  return {variants, [args, variants](const Common& common, OutputSet& outputs) {
            args->shard_given = variants->count("--shard") > 0;
            return run_variants(*args, common, outputs);
          }};
}

}  // namespace cutaway::cli
