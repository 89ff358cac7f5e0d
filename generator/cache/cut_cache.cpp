#include "cache/cut_cache.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <system_error>
#include <vector>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/file_read.h"
#include "base/hash.h"
#include "base/byte_stream.h"

namespace cutaway {

namespace fs = std::filesystem;

namespace {

/// The first bytes of every entry: the format and its version.
constexpr std::string_view kMagic = "cutaway cut cache 1\n";

/// Entries are named by this extension; anything else in the folder is not the cache's.
constexpr std::string_view kEntryExtension = ".cut";

/// Temporary files left by a run killed mid-write are removed after this long.
constexpr auto kStaleTemporary = std::chrono::hours(1);

/// An entry's bytes: magic, key, payload, then fnv1a64 of everything before it.
std::string entry_bytes(std::string_view key, std::string_view payload) {
  ByteWriter w;
  for (char c : kMagic) w.put(c);
  w.put_string(key);
  w.put_string(payload);
  w.put<uint64_t>(fnv1a64(w.bytes()));
  return w.take();
}

/// What reading an entry found.
struct EntryRead {
  bool damaged = false;
  std::string reason;              ///< with `damaged`
  std::string key;                 ///< the stored key (when not damaged)
  std::string payload;
};

EntryRead read_entry(const std::string& bytes) {
  EntryRead r;
  try {
    if (bytes.size() < kMagic.size() + 8 || std::string_view(bytes).substr(0, kMagic.size()) !=
                                                kMagic)
      throw ByteStreamError("not a cut cache entry of this version");
    const std::string_view body(bytes.data(), bytes.size() - 8);
    ByteReader tail(std::string_view(bytes).substr(body.size()));
    if (tail.get<uint64_t>() != fnv1a64(body)) throw ByteStreamError("its check hash differs");
    ByteReader in(body.substr(kMagic.size()));
    r.key = in.get_string();
    r.payload = in.get_string();
    if (!in.done()) throw ByteStreamError("bytes after its payload");
  } catch (const ByteStreamError& e) {
    r.damaged = true;
    r.reason = e.what();
  }
  return r;
}

/// One entry of the folder, for eviction.
struct EntryFile {
  fs::path path;
  fs::file_time_type time;
  uint64_t bytes = 0;
};

/// Every entry under `dir` (and removes temporary files older than kStaleTemporary).
std::vector<EntryFile> scan_entries(const fs::path& dir) {
  std::vector<EntryFile> entries;
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    std::error_code e2;
    if (!it->is_regular_file(e2)) continue;
    const fs::path& p = it->path();
    const auto time = it->last_write_time(e2);
    if (e2) continue;
    if (p.filename().string().find(".tmp-") != std::string::npos) {
      if (now - time > kStaleTemporary) fs::remove(p, e2);
      continue;
    }
    if (p.extension() != kEntryExtension) continue;
    const uint64_t size = it->file_size(e2);
    if (!e2) entries.push_back({p, time, size});
  }
  return entries;
}

}  // namespace

CutCache::CutCache(CutCacheOptions options) : options_(std::move(options)) {
  if (options_.dir.empty()) throw InternalError("CutCache: no folder");
}

fs::path CutCache::default_dir() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && fs::path(xdg).is_absolute()) return fs::path(xdg) / "cutaway";
  const char* home = std::getenv("HOME");
  if (home && *home) return fs::path(home) / ".cache" / "cutaway";
  return {};
}

fs::path CutCache::entry_path(std::string_view key) const {
  const std::string name = hex64(fnv1a64(key));
  return options_.dir / name.substr(0, 2) / (name + std::string(kEntryExtension));
}

void CutCache::warn(const std::string& message) {
  if (options_.warn) options_.warn(message);
}

std::optional<std::string> CutCache::load(std::string_view key) {
  const fs::path path = entry_path(key);
  std::string bytes;
  try {
    bytes = read_regular_file(path, kMaxReadBackBytes);
  } catch (const FileReadError&) {  // none (or unreadable, or removed by another run's eviction)
    std::lock_guard lock(mutex_);
    ++stats_.misses;
    return std::nullopt;
  }
  EntryRead entry = read_entry(bytes);
  std::lock_guard lock(mutex_);
  if (entry.damaged) {
    ++stats_.damaged;
    ++stats_.misses;
    std::error_code ec;
    fs::remove(path, ec);
    warn("cut cache: the entry " + path.string() + " is damaged (" + entry.reason +
         "); it is made again");
    return std::nullopt;
  }
  if (entry.key != key) {  // another key with the same hash: it is replaced when stored
    ++stats_.misses;
    return std::nullopt;
  }
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
  ++stats_.hits;
  return std::move(entry.payload);
}

void CutCache::store(std::string_view key, std::string_view payload) {
  {
    std::lock_guard lock(mutex_);
    if (write_failed_) return;
  }
  // Written outside the lock: objects made side by side store at once (the file is renamed
  // into place whole, so a reader never sees part of it).
  const std::string bytes = entry_bytes(key, payload);
  std::optional<std::string> failure;
  try {
    write_file_atomically(entry_path(key), bytes);
  } catch (const EnvironmentError& e) {
    failure = e.what();
  }
  std::lock_guard lock(mutex_);
  if (failure) {
    if (!write_failed_)  // warned once, by the first store that failed
      warn("cut cache: " + *failure + "; this run stores no more entries");
    write_failed_ = true;
    return;
  }
  ++stats_.stored;
  if (!used_bytes_) {
    uint64_t used = 0;
    for (const EntryFile& f : scan_entries(options_.dir)) used += f.bytes;
    used_bytes_ = used;
  } else {
    *used_bytes_ += bytes.size();
  }
  if (*used_bytes_ > options_.max_bytes) evict_beyond_bound();
}

void CutCache::evict_beyond_bound() {
  // Down to three quarters of the bound, so that the next stores do not each scan again.
  std::vector<EntryFile> entries = scan_entries(options_.dir);
  std::sort(entries.begin(), entries.end(), [](const EntryFile& a, const EntryFile& b) {
    return a.time != b.time ? a.time < b.time : a.path < b.path;
  });
  uint64_t used = 0;
  for (const EntryFile& f : entries) used += f.bytes;
  const uint64_t target = options_.max_bytes / 4 * 3;
  for (const EntryFile& f : entries) {
    if (used <= target) break;
    std::error_code ec;
    if (fs::remove(f.path, ec)) ++stats_.evicted;
    used -= f.bytes;
  }
  used_bytes_ = used;
}

CutCacheStats CutCache::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace cutaway
