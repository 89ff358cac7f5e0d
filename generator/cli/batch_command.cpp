// `cutaway batch`: asset batches, sharded runs and their Slurm array jobs, and `batch merge`
// (doc/batch-format.md). Argument checks and calls into batch/ only.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

#include <spdlog/spdlog.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "batch/batch_manifest.h"
#include "batch/batch_runner.h"
#include "batch/slurm_job.h"
#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "io/batch_parser.h"
#include "render/image/contact_sheet.h"
#include "render/image/image.h"
#include "render/scene_preview.h"

namespace cutaway::cli {

namespace {

namespace fs = std::filesystem;

/// The --sampling and --directions values of `common`, as the command line spells them.
std::string sampling_value(const Common& common) {
  return common.sampling == CapSampling::Dense ? "dense" : "adaptive";
}
std::string directions_value(const Common& common) {
  return common.adaptive_directions ? "adaptive" : "every";
}

/// What else changes an asset's bytes besides the batch file: the backend, sampling and
/// directions.
std::string build_settings(const Common& common) {
  return "backend=" + common.backend + " sampling=" + sampling_value(common) +
         " directions=" + directions_value(common);
}

/// The command line options every array task passes on (those that change the output).
std::vector<std::string> passed_on(const Common& common) {
  return {"--backend",    common.backend,           "--sampling", sampling_value(common),
          "--directions", directions_value(common), "-q"};
}

/// Writes the sbatch script of the batch into DIR and submits it (unless --dry-run).
int submit_slurm(const BatchArgs& a, const Batch& batch, const Common& common) {
  SlurmJob job;
  job.cutaway = fs::read_symlink("/proc/self/exe").string();
  job.batch_file = fs::absolute(a.batch_path).lexically_normal().string();
  job.dir = fs::absolute(a.output_dir).lexically_normal().string();
  job.job_name = batch.name;
  job.array = a.array;
  job.cpus_per_task = a.cpus_per_task;
  job.partition = a.partition;
  job.time = a.time;
  job.extra_args = passed_on(common);
  if (const std::string rule = slurm_job_rule(job); !rule.empty()) throw UsageError(rule);
  fs::create_directories(fs::path(job.dir) / "slurm");
  const fs::path script = fs::path(job.dir) / "batch.sbatch";
  write_file_atomically(script, sbatch_script(job));
  if (a.dry_run) {
    spdlog::info("wrote {} (not submitted: --dry-run)", script.string());
    return 0;
  }
  const std::string id = submit_sbatch(script);
  std::printf("%s\n", id.c_str());
  spdlog::info("submitted {} as job {}: {} array tasks; when it is done: cutaway batch merge {}",
               script.string(), id, a.array, job.dir);
  return 0;
}

}  // namespace

int run_batch_command(const BatchArgs& a, const Common& common, bool quiet) {
  if (a.batch_path.empty()) throw UsageError("give a batch file (BATCH.yaml) or merge DIR");
  if (a.output_dir.empty()) throw UsageError("-o DIR is required");
  std::optional<Shard> shard;
  if (!a.shard.empty()) {
    const Outcome<Shard> parsed = parse_shard(a.shard);
    if (!parsed) throw UsageError("--shard: " + parsed.reason());
    shard = *parsed;
  }
  if (a.slurm && shard) throw UsageError("--slurm: give --array M, not --shard");
  std::error_code ec;
  if (fs::exists(a.output_dir, ec) && !fs::is_directory(a.output_dir, ec))
    throw OutputPathError("-o " + a.output_dir + ": is not a directory");
  const Batch batch = load_batch(a.batch_path);
  if (a.slurm) return submit_slurm(a, batch, common);

  const BatchPlan plan = plan_batch(batch, build_settings(common));
  BatchRunOptions options;
  options.shard = shard;
  options.build.sampling = common.sampling;
  options.build.diffusion = diffusion_factory(batch.export_options.cube, common);
  options.build.thumbnail = [](const SceneAssets& assets) {
    return encode_png(render_scene_preview(assets));
  };
  const ShardRange range = shard_range(plan, shard);
  const ProgressBar bar("batch", static_cast<int>(range.last_unit - range.first_unit),
                        !quiet && isatty(fileno(stderr)));
  const size_t assets = range.last_asset - range.first_asset;
  bar.show(0);
  options.progress = [&](const BatchProgress& p) {
    bar.show(static_cast<int>(p.units_done));
    if (bar.enabled()) return;
    const size_t done = p.assets_built + p.assets_skipped;
    for (size_t i = 0; i < p.assets.size(); ++i)
      spdlog::info("[{}/{}] {}: {}", done - p.assets.size() + i + 1, assets, p.assets[i],
                   p.skipped ? "already there" : "built");
  };
  const BatchRunResult r = run_batch(batch, plan, a.output_dir, options);
  spdlog::info("{}{}: {} assets built, {} already there, {} in {}", batch.name,
               shard ? " shard " + a.shard : "", r.built, r.skipped,
               manifest_name(shard), a.output_dir);
  return 0;
}

int run_batch_merge(const std::string& dir) {
  const Outcome<BatchIndex> index = read_batch_index(dir);
  if (!index) throw UsageError("batch merge: " + index.reason());
  const MergeReport report = merge_manifests(*index, dir);
  const auto list = [](const char* what, const std::vector<std::string>& names) {
    if (names.empty()) return;
    std::string shown;
    for (size_t i = 0; i < names.size() && i < 10; ++i) shown += (i ? ", " : "") + names[i];
    if (names.size() > 10) shown += ", ...";
    spdlog::warn("{} {}: {}", names.size(), what, shown);
  };
  spdlog::info("{}: {} manifest(s), {} of {} assets intact", index->batch,
               report.manifests.size(), report.records.size(), index->assets.size());
  list("assets missing (in no manifest)", report.missing);
  list("assets listed by several manifests (identically; kept once)", report.duplicated);
  list("assets listed differently by several manifests", report.conflicting);
  list("assets whose files are missing or changed", report.damaged);
  list("records of files not in this batch (ignored)", report.unknown);
  if (report.bad_lines > 0)
    spdlog::warn("{} manifest line(s) are not records (cut short?) and were ignored",
                 report.bad_lines);
  if (!report.complete()) {
    std::fprintf(stderr,
                 "cutaway: batch merge: the batch is incomplete; run the missing shards again "
                 "(they skip what is done), then merge\n");
    return kExitBatchIncomplete;
  }
  // The contact sheet: the sample's thumbnails, labelled. A complete report has one record per
  // indexed asset, in the index's order. They are read before anything is written, so that a
  // damaged one leaves the folder as it was.
  CUTAWAY_CHECK(report.records.size() == index->assets.size());
  std::vector<Image> tiles;
  for (size_t i = 0; i < report.records.size(); ++i) {
    const AssetRecord& r = report.records[i];
    if (!index->assets[i].sample || r.thumbnail.empty()) continue;
    const fs::path thumbnail = fs::path(dir) / r.thumbnail;
    Image picture;
    try {
      picture = decode_png(read_file_bytes(thumbnail));
    } catch (const std::runtime_error& e) {
      throw UsageError("batch merge: the thumbnail " + thumbnail.string() + " cannot be used (" +
                       e.what() + "); remove it and its asset and run that shard again");
    }
    tiles.push_back(labelled_tile(picture, r.template_name + "-" + std::to_string(r.seed), r.cut,
                                  std::max(1, picture.width / 160)));
  }
  std::string lines;
  for (const AssetRecord& r : report.records) lines += manifest_line(r);
  write_file_atomically(fs::path(dir) / "manifest.jsonl", lines);
  if (!tiles.empty()) {
    const int columns = static_cast<int>(std::ceil(std::sqrt(4.0 / 3.0 * tiles.size())));
    write_png(fs::path(dir) / "contact-sheet.png", compose_grid(tiles, columns));
  }
  spdlog::info("wrote manifest.jsonl ({} assets){} in {}", report.records.size(),
               tiles.empty() ? "" : ", contact-sheet.png (" + std::to_string(tiles.size()) + " assets)",
               dir);
  return 0;
}

}  // namespace cutaway::cli
