// The files that describe a batch's output folder (doc/batch-format.md, Output folder):
//  - batch.json: the batch index, every asset the batch makes (name, fingerprint, sample),
//    written identically by every shard;
//  - manifest.jsonl (an unsharded run, or `batch merge`) and manifest-K-of-M.jsonl (shard K
//    of M): JSON Lines, one AssetRecord per asset, in batch order, nothing that differs
//    between two runs of the same batch;
// and the checks that resume a run and merge shards.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/outcome.h"
#include "batch/batch_assets.h"
#include "batch/variant_batch.h"

namespace cutaway {

/// The JSON Lines file `stem` of a run: "STEM.jsonl" unsharded, "STEM-K-of-M.jsonl" for shard
/// K/M (the manifest: stem "manifest"; the timings log: "timings").
std::string shard_file_name(const std::string& stem, const std::optional<Shard>& shard);

/// The manifest file of a run: shard_file_name("manifest", shard).
inline std::string manifest_name(const std::optional<Shard>& shard) {
  return shard_file_name("manifest", shard);
}

/// `r` as one line of JSON ending in '\n', keys in this order: file, template, seed, cut,
/// pieces, triangles, vertices, volume_m3, fnv1a64 (16 hex digits), model and model_fnv1a64 (when a
/// model is written), thumbnail and thumbnail_fnv1a64 (when a thumbnail is), inputs.
std::string manifest_line(const AssetRecord& r);

/// The record of one manifest line (as manifest_line writes it; the '\n' may be missing).
/// @returns none with the reason when the line is not such a record
Outcome<AssetRecord> parse_manifest_line(std::string_view line);

/// The records of the manifest at `path`, in file order; lines that are not records (a line
/// cut short by a crash) are left out and counted in *bad_lines. A missing file has none.
std::vector<AssetRecord> read_manifest(const std::filesystem::path& path,
                                       size_t* bad_lines = nullptr);

/// Whether every file `r` names (the .glb, the model, the thumbnail) is in folder `dir` with
/// the bytes the record's hash says.
bool record_files_intact(const AssetRecord& r, const std::filesystem::path& dir);

/// One asset of the batch index.
struct IndexedAsset {
  std::string stem;
  uint64_t inputs = 0;
  bool sample = false;
};

/// What batch.json holds.
struct BatchIndex {
  std::string batch;                 ///< the batch's name
  size_t units = 0;                  ///< variants (what shards divide)
  std::vector<IndexedAsset> assets;  ///< in batch order
};

/// The batch index of `plan` (batch.json's bytes: JSON, one asset per line).
std::string batch_index_text(const Batch& batch, const BatchPlan& plan);

/// Reads batch.json in `dir`.
/// @returns none with the reason when it is missing or not a batch index
Outcome<BatchIndex> read_batch_index(const std::filesystem::path& dir);

/// What merge_manifests found.
struct MergeReport {
  std::vector<std::string> manifests;    ///< the manifest files read, sorted
  std::vector<AssetRecord> records;      ///< one per asset found intact, in batch order
  std::vector<std::string> missing;      ///< assets in no manifest, or listed with other inputs
  std::vector<std::string> duplicated;   ///< assets listed identically by several manifests
  std::vector<std::string> conflicting;  ///< assets listed differently by several manifests
  std::vector<std::string> damaged;      ///< assets whose files are missing or changed
  std::vector<std::string> unknown;      ///< records of files not in the batch index
  size_t bad_lines = 0;                  ///< manifest lines that are not records
  /// Whether the merged manifest can be written: every asset found intact, once.
  bool complete() const { return missing.empty() && conflicting.empty() && damaged.empty(); }
};

/// Reads the shard manifests in `dir` (manifest-K-of-M.jsonl; when there are none,
/// manifest.jsonl) and checks them against `index`: every asset listed once with the index's
/// inputs, and its files intact (record_files_intact). Identical lines in several manifests
/// (a shard run twice, or under another shard count) count as duplicated, not as errors.
MergeReport merge_manifests(const BatchIndex& index, const std::filesystem::path& dir);

/// The merged manifest.jsonl of a complete batch: one manifest_line per record, in batch order.
/// @pre report.complete()
std::string merged_manifest(const MergeReport& report);

}  // namespace cutaway
