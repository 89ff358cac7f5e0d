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

/// The format and its version, in every entry's trailer just before its CRC-32.
constexpr std::string_view kMagic = "cutaway cut cache 2\n";

/// Entries are named by this extension; anything else in the folder is not the cache's.
constexpr std::string_view kEntryExtension = ".cut";

/// Temporary files left by a run killed mid-write are removed after this long.
constexpr auto kStaleTemporary = std::chrono::hours(1);

/// An entry is its payload, then a trailer: the key, the key's and the payload's sizes (64-bit
/// counts), kMagic, and the CRC-32 of all bytes before it. The payload comes first so that a
/// read gives it back by cutting the trailer off, without copying (a market's entries hold
/// half a gigabyte). The trailer of `key` after `payload`.
std::string entry_trailer(std::string_view key, std::string_view payload) {
  ByteWriter w;
  for (char c : key) w.put(c);
  w.put<uint64_t>(key.size());
  w.put<uint64_t>(payload.size());
  for (char c : kMagic) w.put(c);
  w.put<uint32_t>(crc32(w.bytes(), crc32(payload)));
  return w.take();
}

/// The fixed part of a trailer after the key: two sizes, kMagic and the CRC-32.
constexpr size_t kTrailerTail = 8 + 8 + kMagic.size() + 4;

/// How entries of version 1 began (their payload followed the key, their check an FNV-1a).
constexpr std::string_view kVersion1Magic = "cutaway cut cache 1\n";

/// What reading an entry found.
struct EntryRead {
  bool old_version = false;  ///< an entry of version 1: not read, replaced when stored
  bool damaged = false;
  std::string reason;       ///< with `damaged`
  std::string_view key;     ///< the stored key (when not damaged), in the entry's bytes
  size_t payload_size = 0;  ///< the payload: the entry's first bytes
};

EntryRead read_entry(std::string_view bytes) {
  EntryRead r;
  if (bytes.starts_with(kVersion1Magic)) {
    r.old_version = true;
    return r;
  }
  try {
    if (bytes.size() < kTrailerTail ||
        bytes.substr(bytes.size() - 4 - kMagic.size(), kMagic.size()) != kMagic)
      throw ByteStreamError("not a cut cache entry of this version");
    ByteReader tail(bytes.substr(bytes.size() - kTrailerTail));
    const uint64_t key_size = tail.get<uint64_t>(), payload_size = tail.get<uint64_t>();
    if (key_size > bytes.size() || payload_size > bytes.size() - key_size ||
        payload_size + key_size + kTrailerTail != bytes.size())
      throw ByteStreamError("its sizes do not add up");
    ByteReader check(bytes.substr(bytes.size() - 4));
    if (check.get<uint32_t>() != crc32(bytes.substr(0, bytes.size() - 4)))
      throw ByteStreamError("its check sum differs");
    r.key = bytes.substr(payload_size, key_size);
    r.payload_size = payload_size;
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
  // An entry of an earlier version, or of another key with the same hash: replaced when
  // stored.
  if (entry.old_version || entry.key != key) {
    ++stats_.misses;
    return std::nullopt;
  }
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
  ++stats_.hits;
  bytes.resize(entry.payload_size);
  return bytes;
}

void CutCache::store(std::string_view key, std::string_view payload) {
  {
    std::lock_guard lock(mutex_);
    if (write_failed_) return;
  }
  // Written outside the lock: objects made side by side store at once (the file is renamed
  // into place whole, so a reader never sees part of it).
  const std::string trailer = entry_trailer(key, payload);
  const std::string_view parts[] = {payload, trailer};
  std::optional<std::string> failure;
  try {
    write_file_atomically(entry_path(key), parts);
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
    *used_bytes_ += payload.size() + trailer.size();
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
