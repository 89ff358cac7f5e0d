// The cut cache (doc/architecture.md, Cut cache): a folder of content-addressed entries, each
// the bytes of one cut object stored under a key text that names everything those bytes
// depend on (cached_cut.h writes both). An entry is found by a hash of its key and holds the
// key itself, so two keys never share an entry even when their hashes agree.
//
// Its own layout, and nothing else: in the folder it is given (DIR) the cache makes one folder
// of its own, DIR/cutaway-cache-v2/, marked by a CACHEDIR.TAG file (the Cache Directory
// Tagging convention), with shard folders 00/ to ff/ holding entries named by 16 hex digits and
// ".cut". It lists, evicts and cleans only there, and only names of that form: any other file
// in DIR or below it is never read, moved or removed. A cutaway-cache-v2 folder without the
// marker is not used.
//
// Safe to share: every file is written through its folder's handle (folder.h), to a temporary
// file renamed into place, so a reader sees a whole entry or none, and a link planted at an
// entry's name is replaced, never followed; shard folders are opened without following links.
// A cache folder that other users can write (or that another user owns) is refused unless
// the caller accepts it (CutCacheOptions::shared). Each entry ends with a CRC-32 of its bytes:
// a damaged one is reported, removed and made again; one of an earlier version is replaced
// without a word. Readers still treat every entry as untrusted input (cached_cut.h checks what
// it decodes, and discard() removes what fails). The folder is kept under a size bound by
// removing the least recently used entries (by modification time, which a read renews).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "base/blob_store.h"
#include "base/folder.h"

namespace cutaway {

/// The default bound of the cache folder: 4 GiB (the market's cut objects take about N MB).
inline constexpr uint64_t kDefaultCutCacheBytes = uint64_t{4} << 30;

/// The largest cache entry read back; a larger file at an entry's name is removed unread.
inline constexpr uint64_t kMaxCutCacheEntryBytes = uint64_t{1} << 30;

/// The folder the cache makes and uses inside the folder it is given.
inline constexpr std::string_view kCutCacheLayout = "cutaway-cache-v2";

/// Where a cut cache is and how large it may grow.
struct CutCacheOptions {
  std::filesystem::path dir;                   ///< created when missing; the cache lives in
                                               ///< dir / kCutCacheLayout
  uint64_t max_bytes = kDefaultCutCacheBytes;  ///< entries beyond it are evicted, oldest first
  /// Told about what does not stop the run: a damaged entry, a folder that cannot be written
  /// (the cache then only reads), a folder refused (the cache then does nothing). May be
  /// empty.
  std::function<void(const std::string&)> warn;
  /// Accept a cache folder that other users can write or that another user owns (a cache
  /// shared by a group: --cache-shared); the folder is then made group-writable (2770).
  bool shared = false;
};

/// What one CutCache did.
struct CutCacheStats {
  int hits = 0;     ///< entries read back
  int misses = 0;   ///< keys not found (including damaged entries)
  int damaged = 0;  ///< entries whose bytes failed their check, removed
  int stored = 0;   ///< entries written
  int evicted = 0;  ///< entries removed to keep the size bound
};

/// Why the cache folder `options.dir` may not be used (its layout folder looked at without
/// following a link, created when missing with its marker), or "" when it may: "DIR/cutaway-
/// cache-v2 is writable by other users (mode 0777); give --cache-shared to share it", "...
/// belongs to another user (uid N)...", "... has no CACHEDIR.TAG: not a cut cache", "is a
/// symbolic link", or an error creating it ("cannot create the folder ...").
std::string cut_cache_folder_rule(const CutCacheOptions& options);

/// A cut cache folder.
class CutCache {
 public:
  /// Opens (creating when missing) the cache's layout in options.dir. A folder refused by
  /// cut_cache_folder_rule is warned about, and the cache then reads and stores nothing.
  explicit CutCache(CutCacheOptions options);

  /// The default folder: $XDG_CACHE_HOME/cutaway when XDG_CACHE_HOME is an absolute path, else
  /// $HOME/.cache/cutaway (the XDG base directory rules); empty when neither is set.
  static std::filesystem::path default_dir();

  /// The payload stored under `key`, or nullopt when there is none. An entry that fails its
  /// check is removed (and warned about). A hit renews the entry's time for the size bound.
  std::optional<std::string> load(std::string_view key);

  /// Removes the entry of `key` (a file at its name that is not a regular file too), with one
  /// warning "cut cache: the entry PATH is damaged (REASON); it is made again": for readers
  /// whose checks of a decoded entry failed (cached_cut.h). Counted as damaged.
  void discard(std::string_view key, const std::string& reason);

  /// Stores `payload` under `key` (atomically: write_file_atomically), then evicts the least
  /// recently used entries while the folder holds more than max_bytes. A write that fails (a
  /// full disk, a read-only folder) is warned about once; the run goes on without storing.
  void store(std::string_view key, std::string_view payload);

  /// The cache as a BlobStore (load, store and discard of this cache), for the steps below it
  /// that keep slow results in it (KTX2 textures); valid while the cache lives.
  BlobStore blob_store();

  CutCacheStats stats() const;
  const std::filesystem::path& dir() const { return options_.dir; }

 private:
  /// The entry file's name (16 hex digits and ".cut") and shard ("xy", its first two digits).
  static std::string entry_name(std::string_view key);
  /// The path of the entry of `key`, for messages.
  std::filesystem::path entry_path(std::string_view key) const;
  void warn(const std::string& message);
  void evict_beyond_bound();

  CutCacheOptions options_;
  Folder root_;  ///< dir / kCutCacheLayout, open; none when refused
  mutable std::mutex mutex_;
  CutCacheStats stats_;
  std::optional<uint64_t> used_bytes_;  ///< the folder's entries, scanned at the first store
  bool write_failed_ = false;
};

}  // namespace cutaway
