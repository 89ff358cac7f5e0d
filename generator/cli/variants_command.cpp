// `cutaway variants`: seeded variants of one template (DS models as glb), their manifest and a
// contact sheet of their mid-height cuts.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include <unistd.h>

#include <spdlog/spdlog.h>

#include "base/atomic_file.h"
#include "base/timer.h"
#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "export/gltf_export.h"
#include "io/template_parser.h"
#include "render/diffusion_backends.h"
#include "render/image/contact_sheet.h"
#include "render/image/image.h"
#include "section/cross_section.h"
#include "variation/variant_batch.h"
#include "variation/variation.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// The horizontal cut of a variant for its contact-sheet tile: the plane y = mid-height of
/// the skin's bounding box, coloured by PMVC with 8 x 8 texels per cube face (a quarter of
/// the rays of `section`'s default 16: enough for a thumbnail); none when it misses the skin.
cutaway::Outcome<cutaway::CrossSection> variant_section(const cutaway::Variant& v,
                                                        const std::string& backend, int threads) {
  const cutaway::DsMesh& skin = v.model.skin().mesh;
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (const auto vh : skin.vertices()) {
    lo = std::min(lo, skin.point(vh)[1]);
    hi = std::max(hi, skin.point(vh)[1]);
  }
  cutaway::Plane plane;
  plane.point = {0, 0.5 * (lo + hi), 0};
  plane.normal = {0, 1, 0};
  const auto diffusion = cutaway::make_diffusion(v.model, {8, threads},
                                                 cutaway::parse_diffusion_choice(backend));
  return cutaway::make_cross_section(v.model, plane, *diffusion, {v.tmpl.edge_m});
}

}  // namespace

int run_variants(const VariantsArgs& a, const Common& common, bool quiet, OutputSet& outputs) {
  cutaway::Shard shard;
  if (a.shard_given) {
    const cutaway::Outcome<cutaway::Shard> parsed = cutaway::parse_shard(a.shard);
    if (!parsed) throw UsageError("--shard: " + parsed.reason());
    shard = *parsed;
  }
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  const std::filesystem::path dir(a.output_dir);
  const int first = shard.begin(a.count), last = shard.end(a.count);
  // Every file is registered (and DIR created) before the first variant is built.
  std::vector<std::filesystem::path> glb_files;
  for (int i = first; i < last; ++i) {
    const uint64_t seed = a.seed + static_cast<uint64_t>(i);
    glb_files.push_back(
        outputs.add("-o", (dir / (tmpl.name + "-" + std::to_string(seed) + ".glb")).string()));
  }
  const std::filesystem::path manifest_file = outputs.add("-o", (dir / "manifest.json").string());
  const std::filesystem::path sheet_file =
      a.sheet > 0 ? outputs.add("-o", (dir / "contact-sheet.png").string())
                  : std::filesystem::path();
  std::vector<cutaway::VariantRecord> records;
  const ProgressBar progress("variants", last - first, !quiet && isatty(fileno(stderr)));
  progress.show(0);
  std::vector<cutaway::CrossSection> sections;
  std::vector<int> missing;  // sheet tiles whose plane gave no section
  for (int i = first; i < last; ++i) {
    const uint64_t seed = a.seed + static_cast<uint64_t>(i);
    const auto t0 = Clock::now();
    const cutaway::Variant v = cutaway::make_variant(tmpl, seed);
    const std::string glb = cutaway::model_to_glb(v.model, cutaway::GltfModelOptions{});
    const std::string file = tmpl.name + "-" + std::to_string(seed) + ".glb";
    cutaway::write_file_atomically(glb_files[static_cast<size_t>(i - first)], glb);
    records.push_back({file, seed, cutaway::fnv1a64(glb), v.model.face_count(), v.tmpl.folds});
    spdlog::debug("wrote {} ({:.2f} s)", (dir / file).string(), seconds_since(t0));
    progress.show(i - first + 1);
  }
  cutaway::write_file_atomically(
      manifest_file, cutaway::variant_manifest(
                         tmpl.name, a.shard_given ? std::optional(shard) : std::nullopt, records));
  // The contact sheet comes last (all files are committed together, or none); its variants
  // are built again (same seed, same model) rather than all kept.
  for (int i = first; i < std::min(last, first + a.sheet); ++i) {
    const uint64_t seed = a.seed + static_cast<uint64_t>(i);
    cutaway::Outcome<cutaway::CrossSection> section =
        variant_section(cutaway::make_variant(tmpl, seed), common.backend, common.threads);
    if (section) {
      sections.push_back(std::move(*section));
    } else {
      spdlog::warn("seed {}: no horizontal section at mid-height ({}); its tile stays empty",
                   seed, section.reason());
      missing.push_back(i - first);
    }
  }
  if (!sections.empty()) {
    cutaway::SectionTileOptions tile_options;
    tile_options.tile_px = a.tile;
    std::vector<cutaway::Image> tiles = cutaway::render_section_tiles(sections, tile_options);
    for (int m : missing) {  // an empty tile of the same size where a section is missing
      cutaway::Image blank = tiles.front();
      std::fill(blank.rgba.begin(), blank.rgba.end(), uint8_t{255});
      tiles.insert(tiles.begin() + m, std::move(blank));
    }
    const int columns =
        static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles.size()))));
    cutaway::write_png(sheet_file, cutaway::compose_grid(tiles, columns));
  }
  spdlog::info("wrote {} variant(s) of {}, manifest.json{} to {}", last - first, tmpl.name,
               sections.empty() ? "" : ", contact-sheet.png", dir.string());
  return 0;
}

}  // namespace cutaway::cli
