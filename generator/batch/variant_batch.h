// Batches of random variants of one template (the `variants` command, doc/architecture.md):
// which seeds a shard of the batch builds, the content hash of each written file, and the
// manifest that lists them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/hash.h"
#include "base/outcome.h"

namespace cutaway {

/// The K-th of M shares of the variants 0..count-1: contiguous blocks, variant i in shard K
/// when floor((K-1) count / M) <= i < floor(K count / M); shares differ by at most one, and
/// the M shards together are the unsharded batch (each variant's seed is the batch's first
/// seed plus its index, whatever the shard).
struct Shard {
  int k = 1, m = 1;  ///< 1 <= k <= m
  /// The first variant index of this shard. @pre count >= 0
  int begin(int count) const { return static_cast<int>(int64_t{k - 1} * count / m); }
  /// One past the last variant index of this shard. @pre count >= 0
  int end(int count) const { return static_cast<int>(int64_t{k} * count / m); }
};

/// The largest M parse_shard accepts.
inline constexpr int kMaxShards = 100000;

/// Parses the `--shard` notation "K/M": whole numbers (decimal digits only, at most six),
/// 1 <= K <= M <= kMaxShards.
/// @returns the shard, or none with the rule that `text` breaks
Outcome<Shard> parse_shard(std::string_view text);

/// One written variant in the manifest.
struct VariantRecord {
  std::string file;     ///< file name in the output folder, e.g. "tomato-7.glb"
  uint64_t seed = 0;    ///< the variant's seed
  uint64_t hash = 0;    ///< fnv1a64 of the file's bytes
  size_t ds_faces = 0;  ///< triangles of the variant's DS model, all surfaces
  int folds = 0;        ///< the variant's fold count (N-fold templates; 0 cylindrical)
};

/// The manifest.json of a batch of variants of template `name`: one object with "template",
/// "shard" ("K/M", only for a sharded run) and "variants", one line per record with file, seed,
/// template, fnv1a64 (16 hex digits), ds_faces and folds: two runs of the same variants give
/// the same manifest (the command logs the timings instead). `name` and the file names are written
/// as given: template names are restricted to a-z, 0-9, '-' and '_' (template-format.md).
std::string variant_manifest(const std::string& name, const std::optional<Shard>& shard,
                             const std::vector<VariantRecord>& records);

}  // namespace cutaway
