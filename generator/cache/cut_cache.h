// The cut cache (doc/architecture.md, Cut cache): a folder of content-addressed entries, each
// the bytes of one cut object stored under a key text that names everything those bytes
// depend on (cached_cut.h writes both). An entry is found by a hash of its key and holds the
// key itself, so two keys never share an entry even when their hashes agree.
//
// Safe to share: entries are written to a temporary file and renamed into place, so a reader
// sees a whole entry or none, and two runs storing the same entry at once store the same bytes.
// Each entry ends with a CRC-32 of its bytes: a damaged one (a disk error, a truncated copy) is
// reported, removed and made again; one of an earlier version is replaced without a word. The
// folder is kept under a size bound by removing the least recently used entries (by
// modification time, which a read renews).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace cutaway {

/// The default bound of the cache folder: 4 GiB (the market's cut objects take about N MB).
inline constexpr uint64_t kDefaultCutCacheBytes = uint64_t{4} << 30;

/// Where a cut cache is and how large it may grow.
struct CutCacheOptions {
  std::filesystem::path dir;                ///< created when missing
  uint64_t max_bytes = kDefaultCutCacheBytes;  ///< entries beyond it are evicted, oldest first
  /// Told about what does not stop the run: a damaged entry, a folder that cannot be written
  /// (the cache then only reads). May be empty.
  std::function<void(const std::string&)> warn;
};

/// What one CutCache did.
struct CutCacheStats {
  int hits = 0;      ///< entries read back
  int misses = 0;    ///< keys not found (including damaged entries)
  int damaged = 0;   ///< entries whose bytes failed their check, removed
  int stored = 0;    ///< entries written
  int evicted = 0;   ///< entries removed to keep the size bound
};

/// A cut cache folder.
class CutCache {
 public:
  explicit CutCache(CutCacheOptions options);

  /// The default folder: $XDG_CACHE_HOME/cutaway when XDG_CACHE_HOME is an absolute path, else
  /// $HOME/.cache/cutaway (the XDG base directory rules); empty when neither is set.
  static std::filesystem::path default_dir();

  /// The payload stored under `key`, or nullopt when there is none. An entry that fails its
  /// check is removed (and warned about). A hit renews the entry's time for the size bound.
  std::optional<std::string> load(std::string_view key);

  /// Stores `payload` under `key` (atomically: write_file_atomically), then evicts the least
  /// recently used entries while the folder holds more than max_bytes. A write that fails (a
  /// full disk, a read-only folder) is warned about once; the run goes on without storing.
  void store(std::string_view key, std::string_view payload);

  CutCacheStats stats() const;
  const std::filesystem::path& dir() const { return options_.dir; }

 private:
  std::filesystem::path entry_path(std::string_view key) const;
  void warn(const std::string& message);
  void evict_beyond_bound();

  CutCacheOptions options_;
  mutable std::mutex mutex_;
  CutCacheStats stats_;
  std::optional<uint64_t> used_bytes_;  ///< the folder's entries, scanned at the first store
  bool write_failed_ = false;
};

}  // namespace cutaway
