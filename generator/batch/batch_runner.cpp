#include "batch/batch_runner.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <map>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/timer.h"
#include "batch/batch_manifest.h"

namespace cutaway {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Appends `text` to the file at `path` (created when missing) and flushes it to disk. A link at
/// `path` is refused (O_NOFOLLOW), never written through.
void append_durably(const fs::path& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw EnvironmentError("cannot write " + path.string() + ": " + std::strerror(errno));
  size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      ::close(fd);
      throw EnvironmentError("cannot write " + path.string() + ": " + std::strerror(err));
    }
    written += static_cast<size_t>(n);
  }
  const bool synced = ::fsync(fd) == 0;
  const int err = errno;
  ::close(fd);
  if (!synced) throw EnvironmentError("cannot write " + path.string() + ": " + std::strerror(err));
}

/// The records of every manifest in `dir`, by file name.
std::multimap<std::string, AssetRecord> known_records(const fs::path& dir) {
  std::multimap<std::string, AssetRecord> known;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (e.symlink_status(ec).type() != fs::file_type::regular || name.rfind("manifest", 0) != 0 ||
        e.path().extension() != ".jsonl")
      continue;
    for (AssetRecord& r : read_manifest(e.path())) known.emplace(r.file, std::move(r));
  }
  return known;
}

/// The record of `asset` among `known` whose inputs match and whose files are intact.
std::optional<AssetRecord> intact_record(const BatchAsset& asset,
                                         const std::multimap<std::string, AssetRecord>& known,
                                         const fs::path& dir) {
  const auto [first, last] = known.equal_range(asset.stem + ".glb");
  for (auto it = first; it != last; ++it)
    if (it->second.inputs == asset.inputs && record_files_intact(it->second, dir))
      return it->second;
  return std::nullopt;
}

}  // namespace

BatchRunResult run_batch(const Batch& batch, const BatchPlan& plan, const fs::path& dir,
                         const BatchRunOptions& options) {
  fs::create_directories(dir);
  const std::string index = batch_index_text(batch, plan);
  write_file_atomically(dir / "batch.json", index);

  const ShardRange range = shard_range(plan, options.shard);
  const size_t first = range.first_unit, last = range.last_unit;
  const size_t asset_begin = range.first_asset, asset_end = range.last_asset;
  const fs::path manifest = dir / manifest_name(options.shard);
  const fs::path timings = dir / shard_file_name("timings", options.shard);

  // Per asset of the shard: its record, when already there.
  const std::multimap<std::string, AssetRecord> known = known_records(dir);
  std::vector<std::optional<AssetRecord>> records(asset_end - asset_begin);
  std::string lines;
  for (size_t a = asset_begin; a < asset_end; ++a) {
    records[a - asset_begin] = intact_record(plan.assets[a], known, dir);
    if (records[a - asset_begin]) lines += manifest_line(*records[a - asset_begin]);
  }
  write_file_atomically(manifest, lines);

  BatchRunResult result;
  result.units = last - first;
  BatchProgress progress;
  progress.units = result.units;
  for (size_t u = first; u < last; ++u) {
    const auto t0 = Clock::now();
    const BatchUnit& unit = plan.units[u];
    const size_t cuts = batch.items[unit.item].cuts.size();
    bool all_there = true;
    for (size_t c = 0; c < cuts; ++c)
      all_there = all_there && records[unit.first_asset + c - asset_begin].has_value();
    UnitTimings t;
    if (all_there) {
      result.skipped += cuts;
    } else {
      std::vector<BuiltAsset> built = build_batch_unit(batch, plan, u, options.build, &t);
      std::string new_lines;
      for (size_t c = 0; c < built.size(); ++c) {
        for (const BatchFile& f : built[c].files) write_file_atomically(dir / f.name, f.bytes);
        new_lines += manifest_line(built[c].record);
        records[unit.first_asset + c - asset_begin] = std::move(built[c].record);
      }
      append_durably(manifest, new_lines);
      result.built += cuts;
    }
    progress.units_done = u - first + 1;
    progress.assets_built = result.built;
    progress.assets_skipped = result.skipped;
    progress.variant = batch.items[unit.item].template_name + "-" + std::to_string(unit.seed);
    progress.skipped = all_there;
    progress.assets.clear();
    for (size_t c = 0; c < cuts; ++c)
      progress.assets.push_back(plan.assets[unit.first_asset + c].stem);
    progress.seconds = seconds_since(t0);
    const nlohmann::ordered_json timing = {{"variant", progress.variant},
                                           {"skipped", all_there},
                                           {"seconds",
                                            {{"total", progress.seconds},
                                             {"variant", t.variant},
                                             {"cut", t.cut},
                                             {"bake", t.bake},
                                             {"export", t.export_glb},
                                             {"thumbnail", t.thumbnail}}}};
    append_durably(timings, timing.dump() + "\n");
    if (options.progress) options.progress(progress);
  }
  lines.clear();
  for (const std::optional<AssetRecord>& r : records) lines += manifest_line(*r);
  write_file_atomically(manifest, lines);
  return result;
}

}  // namespace cutaway
