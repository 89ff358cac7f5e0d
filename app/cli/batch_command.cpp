// `cutaway batch`: asset batches, sharded runs and their Slurm array jobs, and `batch merge`
// (doc/batch-format.md). Argument checks and calls into batch/ only.
#include <cstdio>
#include <filesystem>
#include <memory>

#include <unistd.h>

#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "app/cli/progress_bar.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "batch/batch_manifest.h"
#include "batch/batch_runner.h"
#include "batch/slurm_job.h"
#include "io/batch_parser.h"
#include "render/batch_sheet.h"
#include "render/image/image.h"
#include "render/scene_preview.h"

namespace cutaway::cli {

namespace {

/// `cutaway batch BATCH.yaml -o DIR [--shard K/M]`, or with `--slurm [--array M] [--partition
/// P] [--time T] [--cpus-per-task C] [--dry-run]` an sbatch array script written into DIR and
/// submitted ( doc/batch-format.md).
struct BatchArgs {
  std::string batch_path, output_dir, shard;  ///< shard: "" for the whole batch
  bool slurm = false, dry_run = false;
  int array = 4, cpus_per_task = 1;
  std::string partition, time;
  CacheArgs cache;
};

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

/// The command line options every array task passes on (those that change the output, and
/// the cut cache's).
std::vector<std::string> passed_on(const Common& common, const CacheArgs& cache) {
  std::vector<std::string> args = {
      "--backend",    common.backend,           "--sampling", sampling_value(common),
      "--directions", directions_value(common), "-q"};
  if (cache.off) args.push_back("--no-cache");
  if (!cache.dir.empty())
    args.insert(args.end(), {"--cache", fs::absolute(cache.dir).lexically_normal().string()});
  if (cache.max_bytes > 0)
    args.insert(args.end(), {"--cache-size", std::to_string(cache.max_bytes)});
  if (cache.shared) args.push_back("--cache-shared");
  return args;
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
  job.extra_args = passed_on(common, a.cache);
  if (const Check ok = check_slurm_job(job); !ok) throw UsageError(ok.reason());
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

/// `cutaway batch merge DIR`: checks the shards' manifests against batch.json, writes
/// manifest.jsonl and contact-sheet.png (the sample's thumbnails, labelled) when every asset is
/// there; returns kExitBatchIncomplete when the batch is incomplete.
int run_batch_merge(const std::string& dir, OutputSet& outputs) {
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
  spdlog::info("{}: {} manifest(s), {} of {} assets intact", index->batch, report.manifests.size(),
               report.records.size(), index->assets.size());
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
  // The contact sheet's thumbnails are read before anything is written, so that a damaged one
  // leaves the folder as it was; both files are committed together (run_command).
  const Outcome<BatchSheet> sheet = batch_contact_sheet(*index, report, dir);
  if (!sheet) throw UsageError("batch merge: " + sheet.reason());
  write_file_atomically(outputs.add("DIR", fs::path(dir) / "manifest.jsonl"),
                        merged_manifest(report));
  if (sheet->assets > 0)
    write_png(outputs.add("DIR", fs::path(dir) / "contact-sheet.png"), sheet->image);
  spdlog::info("wrote manifest.jsonl ({} assets){} in {}", report.records.size(),
               sheet->assets == 0
                   ? ""
                   : ", contact-sheet.png (" + std::to_string(sheet->assets) + " assets)",
               dir);
  return 0;
}

int run_batch_command(const BatchArgs& a, const Common& common) {
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
  Batch batch = load_batch(a.batch_path);
  if (batch.export_options.gltf.textures == TextureFormat::Ktx2)
    batch.export_options.gltf.basisu = require_basisu(a.batch_path + ": export.textures: ktx2");
  if (a.slurm) return submit_slurm(a, batch, common);

  const BatchPlan plan = plan_batch(batch, build_settings(common));
  BatchRunOptions options;
  options.shard = shard;
  options.build.sampling = common.sampling;
  // Resolved after the plan: the fingerprints name --backend as given ("auto" on every node).
  const Common resolved = with_resolved_backend(common);
  options.build.diffusion = diffusion_factory(batch.export_options.cube, resolved);
  options.build.diffusion_settings = diffusion_settings(batch.export_options.cube, resolved);
  const std::unique_ptr<CutCache> cache = open_cut_cache(a.cache);
  options.build.cache = cache.get();
  options.build.thumbnail = [](const SceneAssets& assets) {
    return encode_png(render_scene_preview(assets));
  };
  const ShardRange range = shard_range(plan, shard);
  const ProgressBar bar("batch", static_cast<int>(range.last_unit - range.first_unit),
                        !common.quiet && isatty(fileno(stderr)));
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
               shard ? " shard " + a.shard : "", r.built, r.skipped, manifest_name(shard),
               a.output_dir);
  if (cache && cache->stats().hits > 0)
    spdlog::info("{} of the assets built were read from the cut cache", cache->stats().hits);
  if (common.stats)
    *common.stats = {{"batch", batch.name},
                     {"shard", a.shard},
                     {"assets_built", r.built},
                     {"assets_already_there", r.skipped},
                     {"cut_cache", cut_cache_stats(cache.get())}};
  return 0;
}

}  // namespace

Command add_batch_command(CLI::App& app) {
  auto args = std::make_shared<BatchArgs>();
  CLI::App* batch = app.add_subcommand(
      "batch", "asset batches: solid cut pieces per variant and cut, sharded, resumable, on "
               "Slurm (doc/batch-format.md)");
  batch->require_subcommand(0, 1);
  batch->add_option("BATCH", args->batch_path, "batch file (.yaml)");
  batch->add_option("-o,--output", args->output_dir, "output folder");
  batch
      ->add_option("--shard", args->shard,
                   "K/M: build only the K-th of M contiguous shares of the variants")
      ->check(shard_rule());
  batch->add_flag("--slurm", args->slurm,
                  "write DIR/batch.sbatch, an sbatch array job of --array shards, and submit it");
  batch->add_option("--array", args->array, "with --slurm: array tasks (shards; default 4)")
      ->check(number_rule(1, 100000));
  batch->add_option("--partition", args->partition, "with --slurm: the Slurm partition");
  batch->add_option("--time", args->time, "with --slurm: each task's time limit (e.g. 2:00:00)");
  batch
      ->add_option("--cpus-per-task", args->cpus_per_task,
                   "with --slurm: CPUs per task, its --threads (default 1)")
      ->check(number_rule(1, 1024));
  batch->add_flag("--dry-run", args->dry_run, "with --slurm: write the script, do not submit");
  add_cache_options(batch, args->cache);
  auto merge_dir = std::make_shared<std::string>();
  CLI::App* merge = batch->add_subcommand(
      "merge", "check and merge the shards' manifests of DIR; write manifest.jsonl and "
               "contact-sheet.png");
  merge->add_option("DIR", *merge_dir, "the batch's output folder")->required();
  return {batch, [args, merge, merge_dir](const Common& common, OutputSet& outputs) {
            return *merge ? run_batch_merge(*merge_dir, outputs) : run_batch_command(*args, common);
          }};
}

}  // namespace cutaway::cli
