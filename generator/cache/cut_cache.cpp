#include "cache/cut_cache.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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

/// The marker of the cache's own folder (the Cache Directory Tagging convention): backup tools
/// skip the folder, and the cache uses a layout folder only when it holds this file.
constexpr std::string_view kMarkerName = "CACHEDIR.TAG";
constexpr std::string_view kMarker =
    "Signature: 8a477f597d28d172789f06886806bc55\n"
    "# This file is a cache directory tag created by cutaway: the cut cache.\n"
    "# See doc/command-line.md of cutaway, The cut cache.\n";

bool hex_digits(std::string_view text) {
  return std::all_of(text.begin(), text.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

/// A shard folder's name: two hex digits.
bool shard_name(std::string_view name) { return name.size() == 2 && hex_digits(name); }

/// An entry's name: 16 hex digits and ".cut".
bool entry_file_name(std::string_view name) {
  return name.size() == 16 + kEntryExtension.size() && name.ends_with(kEntryExtension) &&
         hex_digits(name.substr(0, 16));
}

/// A temporary file of an entry (Folder::write_atomically): NAME.tmp- and six letters or digits.
bool temporary_name(std::string_view name) {
  constexpr size_t kStem = 16 + kEntryExtension.size();
  if (name.size() != kStem + 5 + 6 || !entry_file_name(name.substr(0, kStem)) ||
      name.substr(kStem, 5) != ".tmp-")
    return false;
  return std::all_of(name.begin() + kStem + 5, name.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; });
}

/// One entry of the folder, for eviction.
struct EntryFile {
  Folder shard;
  std::string name;
  struct timespec time {};
  uint64_t bytes = 0;
};

/// Every entry of the layout folder `root` (and removes its own temporary files older than
/// kStaleTemporary). Looks only at shard folders (two hex digits, not links) and, in them,
/// regular files named as entries or their temporaries.
std::vector<EntryFile> scan_entries(const Folder& root) {
  std::vector<EntryFile> entries;
  struct timespec now {};
  ::clock_gettime(CLOCK_REALTIME, &now);
  const auto stale_s = std::chrono::duration_cast<std::chrono::seconds>(kStaleTemporary).count();
  try {
    for (const std::string& shard_dir : root.names()) {
      if (!shard_name(shard_dir) || root.kind(shard_dir) != EntryKind::Directory) continue;
      const Folder shard = root.sub(shard_dir, false);
      for (const std::string& name : shard.names()) {
        const bool entry = entry_file_name(name), temporary = !entry && temporary_name(name);
        if (!entry && !temporary) continue;
        struct stat st;
        if (::fstatat(shard.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 ||
            !S_ISREG(st.st_mode))
          continue;
        if (temporary) {
          if (now.tv_sec - st.st_mtim.tv_sec > stale_s) shard.remove(name);
          continue;
        }
        entries.push_back({shard, name, st.st_mtim, static_cast<uint64_t>(st.st_size)});
      }
    }
  } catch (const EnvironmentError&) {
    // A shard that vanished or cannot be listed (another run's eviction): what was found counts.
  }
  return entries;
}

/// The owner and mode rule of the layout folder open as `root`, "" when it may be used.
std::string ownership_rule(const Folder& root, bool shared) {
  struct stat st;
  if (::fstat(root.fd(), &st) != 0) return "cannot look at " + root.path().string();
  if (shared) return "";
  char mode[8];
  std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
  if (st.st_uid != ::geteuid())
    return root.path().string() + " belongs to another user (uid " + std::to_string(st.st_uid) +
           "); give --cache-shared to share it";
  if (st.st_mode & (S_IWGRP | S_IWOTH))
    return root.path().string() + " is writable by other users (mode " + mode +
           "); give --cache-shared to share it";
  return "";
}

/// Makes the layout folder in `dir` whole or not at all: a fresh folder (a watched temporary
/// ".cutaway-cache-v2.tmp-XXXXXX") with its marker, renamed into place. When another run made
/// the layout meanwhile, ours is removed and theirs is used.
void make_layout(const Folder& dir, mode_t mode) {
  RemoveOnSignal guard;
  const std::string name(kCutCacheLayout);
  const fs::path made =
      create_watched("." + name + ".tmp-", RemoveOnSignal::Kind::Folder, guard, nullptr, &dir);
  if (made.empty())
    throw EnvironmentError("cannot create the folder " + (dir.path() / name).string() + ": " +
                           std::strerror(errno));
  const std::string tmp = made.filename().string();
  const Folder fresh = dir.sub(tmp, false);
  const std::string_view marker[] = {kMarker};
  fresh.write_atomically(kMarkerName, marker);
  ::fchmod(fresh.fd(), mode);  // past the umask
  if (::renameat(dir.fd(), tmp.c_str(), dir.fd(), name.c_str()) != 0) {
    fresh.remove(kMarkerName);
    dir.remove(tmp);
  }
}

/// Opens (making it when missing, with its marker) the layout folder in options.dir; sets
/// `rule` and returns no folder when it may not be used.
Folder open_layout(const CutCacheOptions& options, std::string& rule) {
  try {
    const Folder dir = Folder::open(options.dir, true);
    const std::string name(kCutCacheLayout);
    if (dir.kind(name) == EntryKind::Missing) make_layout(dir, options.shared ? 02770 : 0700);
    Folder root = dir.sub(name, false);
    rule = ownership_rule(root, options.shared);
    if (!rule.empty()) return {};
    if (root.kind(kMarkerName) != EntryKind::Regular) {
      rule = root.path().string() + " has no " + std::string(kMarkerName) +
             ": not a cut cache (remove the folder, or give another --cache)";
      return {};
    }
    return root;
  } catch (const EnvironmentError& e) {
    rule = e.what();
    return {};
  }
}

}  // namespace

std::string cut_cache_folder_rule(const CutCacheOptions& options) {
  std::string rule;
  open_layout(options, rule);
  return rule;
}

CutCache::CutCache(CutCacheOptions options) : options_(std::move(options)) {
  if (options_.dir.empty()) throw InternalError("CutCache: no folder");
  std::string rule;
  root_ = open_layout(options_, rule);
  if (!root_) warn("cut cache: not used: " + rule);
}

fs::path CutCache::default_dir() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && fs::path(xdg).is_absolute()) return fs::path(xdg) / "cutaway";
  const char* home = std::getenv("HOME");
  if (home && *home) return fs::path(home) / ".cache" / "cutaway";
  return {};
}

std::string CutCache::entry_name(std::string_view key) {
  return hex64(fnv1a64(key)) + std::string(kEntryExtension);
}

fs::path CutCache::entry_path(std::string_view key) const {
  const std::string name = entry_name(key);
  return options_.dir / kCutCacheLayout / name.substr(0, 2) / name;
}

void CutCache::warn(const std::string& message) {
  if (options_.warn) options_.warn(message);
}

std::optional<std::string> CutCache::load(std::string_view key) {
  const auto miss = [&] {
    std::lock_guard lock(mutex_);
    ++stats_.misses;
    return std::nullopt;
  };
  if (!root_) return miss();
  const std::string name = entry_name(key);
  std::string bytes;
  Folder shard;
  try {
    shard = root_.sub(name.substr(0, 2), false);
    bytes = shard.read(name, kMaxCutCacheEntryBytes);
  } catch (const FileReadError& e) {
    // None, or something at the entry's name that no entry can be (a link, a FIFO, a folder,
    // a file over the bound): ours by its name, so removed; the rest of the cache works on.
    // Decided by what lies there, not by the message: gone meanwhile (another run's
    // eviction) or a read error of a real entry is a plain miss.
    struct stat st;
    const bool foreign =
        shard && ::fstatat(shard.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 &&
        (!S_ISREG(st.st_mode) || static_cast<uint64_t>(st.st_size) > kMaxCutCacheEntryBytes);
    if (foreign) {
      const bool removed = shard.remove(name);
      std::lock_guard lock(mutex_);
      ++stats_.damaged;
      warn("cut cache: " + std::string(e.what()) + (removed ? "; removed" : "; skipped") +
           ", the entry is made again");
    }
    return miss();
  } catch (const EnvironmentError&) {  // no shard yet, or a link in its place
    return miss();
  }
  EntryRead entry = read_entry(bytes);
  std::lock_guard lock(mutex_);
  if (entry.damaged) {
    ++stats_.damaged;
    ++stats_.misses;
    shard.remove(name);
    warn("cut cache: the entry " + entry_path(key).string() + " is damaged (" + entry.reason +
         "); it is made again");
    return std::nullopt;
  }
  // An entry of an earlier version, or of another key with the same hash: replaced when
  // stored.
  if (entry.old_version || entry.key != key) {
    ++stats_.misses;
    return std::nullopt;
  }
  ::utimensat(shard.fd(), name.c_str(), nullptr, AT_SYMLINK_NOFOLLOW);
  ++stats_.hits;
  bytes.resize(entry.payload_size);
  return bytes;
}

BlobStore CutCache::blob_store() {
  return {[this](std::string_view key) { return load(key); },
          [this](std::string_view key, std::string_view bytes) { store(key, bytes); },
          [this](std::string_view key, const std::string& reason) { discard(key, reason); }};
}

void CutCache::discard(std::string_view key, const std::string& reason) {
  if (!root_) return;
  const std::string name = entry_name(key);
  try {
    root_.sub(name.substr(0, 2), false).remove(name);
  } catch (const EnvironmentError&) {
    // Its shard is gone already.
  }
  std::lock_guard lock(mutex_);
  ++stats_.damaged;
  warn("cut cache: the entry " + entry_path(key).string() + " is damaged (" + reason +
       "); it is made again");
}

void CutCache::store(std::string_view key, std::string_view payload) {
  {
    std::lock_guard lock(mutex_);
    if (write_failed_ || !root_) return;
  }
  // Written outside the lock: objects made side by side store at once (the file is renamed
  // into place whole, so a reader never sees part of it).
  const std::string trailer = entry_trailer(key, payload);
  const std::string_view parts[] = {payload, trailer};
  const std::string name = entry_name(key);
  std::optional<std::string> failure;
  try {
    // Something no shard can be at the shard's name (a link, a file): ours, so removed.
    const std::string shard_dir = name.substr(0, 2);
    if (const EntryKind k = root_.kind(shard_dir);
        k != EntryKind::Missing && k != EntryKind::Directory)
      root_.remove(shard_dir);
    const Folder shard = root_.sub(shard_dir, true, options_.shared ? 02770 : 0700);
    // Something no entry can be at the entry's name (a FIFO, a folder): ours, so removed.
    if (const EntryKind k = shard.kind(name); k == EntryKind::Special || k == EntryKind::Directory)
      shard.remove(name);
    shard.write_atomically(name, parts);
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
    for (const EntryFile& f : scan_entries(root_)) used += f.bytes;
    used_bytes_ = used;
  } else {
    *used_bytes_ += payload.size() + trailer.size();
  }
  if (*used_bytes_ > options_.max_bytes) evict_beyond_bound();
}

void CutCache::evict_beyond_bound() {
  // Down to three quarters of the bound, so that the next stores do not each scan again.
  std::vector<EntryFile> entries = scan_entries(root_);
  std::sort(entries.begin(), entries.end(), [](const EntryFile& a, const EntryFile& b) {
    if (a.time.tv_sec != b.time.tv_sec) return a.time.tv_sec < b.time.tv_sec;
    if (a.time.tv_nsec != b.time.tv_nsec) return a.time.tv_nsec < b.time.tv_nsec;
    return a.name < b.name;
  });
  uint64_t used = 0;
  for (const EntryFile& f : entries) used += f.bytes;
  const uint64_t target = options_.max_bytes / 4 * 3;
  for (const EntryFile& f : entries) {
    if (used <= target) break;
    if (f.shard.remove(f.name)) ++stats_.evicted;
    used -= f.bytes;
  }
  used_bytes_ = used;
}

CutCacheStats CutCache::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace cutaway
