#include "base/atomic_file.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <sstream>
#include <string>

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/error.h"
#include "base/file_read.h"

namespace cutaway {

namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// The paths RemoveOnSignal watches: fixed slots that the signal handler reads without locks or
// allocation. A slot is free (0), being filled (1) or watched (2); only watched slots are
// touched by the handler.

constexpr int kSlots = 128;
constexpr int kFree = 0, kFilling = 1, kWatched = 2;

struct Slot {
  std::atomic<int> state{kFree};
  bool folder = false;
  pid_t child = 0;  // > 0: a child process to stop, not a path
  char path[PATH_MAX];
};
Slot g_slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

constexpr int kSignals[] = {SIGTERM, SIGINT, SIGHUP};

// While OutputSet::commit() renames, a signal is only noted here and raised again once the
// renames are done, so that a catchable signal never splits a commit.
std::atomic<int> g_committing{0};
std::atomic<int> g_deferred_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

// Removes the files directly in the folder `path`, then the folder. System calls only.
void sweep_folder(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    alignas(8) char buf[4096];
    // Entries are deleted while the folder is read, so read it again until a pass finds
    // nothing (bounded, in case something keeps adding files).
    for (int pass = 0; pass < 64; ++pass) {
      bool removed = false;
      ::lseek(fd, 0, SEEK_SET);
      for (;;) {
        const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
        if (n <= 0) break;
        for (long at = 0; at < n;) {
          // struct linux_dirent64: u64 d_ino, s64 d_off, u16 d_reclen, u8 d_type, char d_name[]
          unsigned short reclen;
          std::memcpy(&reclen, buf + at + 16, sizeof reclen);
          const char* name = buf + at + 19;
          if (!(name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0)))) {
            if (::unlinkat(fd, name, 0) == 0) removed = true;
          }
          at += reclen;
        }
      }
      if (!removed) break;
    }
    ::close(fd);
  }
  ::rmdir(path);
}

extern "C" void remove_watched_and_reraise(int sig) {
  const int saved_errno = errno;
  if (g_committing.load(std::memory_order_acquire) != 0) {
    g_deferred_signal.store(sig, std::memory_order_release);
    return;
  }
  // Child processes first, so that none writes into a folder once it is swept; then files,
  // some of which lie in watched folders, which can only go once they are empty.
  for (int pass = 0; pass < 3; ++pass) {
    for (Slot& s : g_slots) {
      if (s.state.load(std::memory_order_acquire) != kWatched) continue;
      if (pass == 0 && s.child > 0 && ::kill(s.child, SIGKILL) == 0) {
        while (::waitpid(s.child, nullptr, 0) < 0 && errno == EINTR) {
        }
      }
      if (s.child > 0) continue;
      if (pass == 1 && !s.folder) ::unlink(s.path);
      if (pass == 2 && s.folder) sweep_folder(s.path);
    }
  }
  struct sigaction dfl;
  std::memset(&dfl, 0, sizeof dfl);
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  errno = saved_errno;
  // Blocked while this handler runs; delivered with the default action when it returns.
  ::raise(sig);
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : kSignals) {
      struct sigaction old;
      if (::sigaction(sig, nullptr, &old) != 0) continue;
      const bool is_default = !(old.sa_flags & SA_SIGINFO) && old.sa_handler == SIG_DFL;
      if (!is_default) continue;  // ignored, or the program's own handler: left alone
      struct sigaction sa;
      std::memset(&sa, 0, sizeof sa);
      sa.sa_handler = remove_watched_and_reraise;
      sigemptyset(&sa.sa_mask);
      for (int other : kSignals) sigaddset(&sa.sa_mask, other);  // one cleanup at a time
      sa.sa_flags = 0;
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

// Fills a free slot with a path (child 0) or a child process; returns it, or -1 when none is
// free.
int watch(const std::string& abs, bool folder, pid_t child) {
  install_handlers();
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(g_slots[i].path, abs.c_str(), abs.size() + 1);
    g_slots[i].folder = folder;
    g_slots[i].child = child;
    g_slots[i].state.store(kWatched, std::memory_order_release);
    return i;
  }
  return -1;
}

int watch_path(const fs::path& path, bool folder) {
  std::error_code ec;
  const std::string abs = fs::absolute(path, ec).string();
  if (ec || abs.size() >= PATH_MAX) return -1;
  return watch(abs, folder, 0);
}

void unwatch(int slot) {
  if (slot >= 0) g_slots[slot].state.store(kFree, std::memory_order_release);
}

// ---------------------------------------------------------------------------------------------

std::string errno_text(int e) { return std::strerror(e); }

// Where writing `path` ends up: symbolic links followed to the end of the chain (the last
// target may not exist). Sets `rule` and returns {} when that fails.
fs::path resolve_links(const fs::path& path, std::string& rule) {
  fs::path cur = path;
  for (int hops = 0; hops <= 40; ++hops) {
    struct stat st;
    if (::lstat(cur.c_str(), &st) != 0) {
      if (errno == ENOENT) return cur;  // a new file (or a missing directory: checked later)
      if (errno == ENOTDIR) {
        rule = "a part of the path is not a directory";
      } else {
        rule = "cannot look at " + cur.string() + ": " + errno_text(errno);
      }
      return {};
    }
    if (!S_ISLNK(st.st_mode)) return cur;
    std::error_code ec;
    const fs::path target = fs::read_symlink(cur, ec);
    if (ec) {
      rule = "cannot read the symbolic link " + cur.string() + ": " + ec.message();
      return {};
    }
    cur = target.is_absolute() ? target : cur.parent_path() / target;
  }
  rule = "too many levels of symbolic links";
  return {};
}

// "" when `path` (links resolved) may be replaced by a regular file, else the rule it breaks.
std::string target_rule(const fs::path& path) {
  struct stat st;
  if (::lstat(path.c_str(), &st) != 0) return "";
  if (S_ISDIR(st.st_mode)) return "is a directory";
  if (!S_ISREG(st.st_mode)) {
    return "is not a regular file (a device, FIFO or socket); outputs must be regular files";
  }
  return "";
}

}  // namespace

// ---------------------------------------------------------------------------------------------

RemoveOnSignal::RemoveOnSignal(const fs::path& path, Kind kind)
    : slot_(watch_path(path, kind == Kind::Folder)) {}

RemoveOnSignal::RemoveOnSignal(pid_t child) : slot_(child > 0 ? watch("", false, child) : -1) {}

RemoveOnSignal::~RemoveOnSignal() { release(); }

RemoveOnSignal::RemoveOnSignal(RemoveOnSignal&& other) noexcept : slot_(other.slot_) {
  other.slot_ = -1;
}

RemoveOnSignal& RemoveOnSignal::operator=(RemoveOnSignal&& other) noexcept {
  if (this != &other) {
    release();
    slot_ = other.slot_;
    other.slot_ = -1;
  }
  return *this;
}

void RemoveOnSignal::release() noexcept {
  unwatch(slot_);
  slot_ = -1;
}

fs::path create_watched(const std::string& prefix, RemoveOnSignal::Kind kind,
                        RemoveOnSignal& guard, int* fd) {
  constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  for (int attempt = 0; attempt < 100; ++attempt) {
    unsigned char random[6];
    if (::getrandom(random, sizeof random, 0) != static_cast<ssize_t>(sizeof random)) return {};
    std::string path = prefix;
    for (const unsigned char r : random) path += kChars[r % (sizeof kChars - 1)];
    guard = RemoveOnSignal(path, kind);
    const bool made =
        kind == RemoveOnSignal::Kind::Folder
            ? ::mkdir(path.c_str(), 0700) == 0
            : (*fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600)) >= 0;
    if (made) return path;
    const int e = errno;
    guard.release();  // not ours: it existed before, or nothing was made
    errno = e;
    if (e != EEXIST) return {};
  }
  errno = EEXIST;
  return {};
}

// ---------------------------------------------------------------------------------------------

std::string read_file_bytes(const std::filesystem::path& path) {
  return read_regular_file(path, kMaxReadBackBytes);
}

void write_file_atomically(const fs::path& given, std::string_view bytes) {
  write_file_atomically(given, std::span<const std::string_view>(&bytes, 1));
}

void write_file_atomically(const fs::path& given, std::span<const std::string_view> parts) {
  std::string rule;
  fs::path path = resolve_links(given, rule);
  if (path.empty()) path = given;  // let the write below report the problem
  rule = target_rule(path);
  if (!rule.empty()) throw EnvironmentError("cannot write " + given.string() + ": " + rule);
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec)  // the real cause, not the "no such file" of the write into a missing folder
    throw EnvironmentError("cannot write " + given.string() + ": cannot create the folder " +
                           parent.string() + ": " + ec.message());
  RemoveOnSignal guard;
  int fd = -1;
  const std::string tmpl =
      create_watched((parent / (path.filename().string() + ".tmp-")).string(),
                     RemoveOnSignal::Kind::File, guard, &fd)
          .string();
  if (tmpl.empty()) {
    throw EnvironmentError("cannot write " + given.string() + ": cannot create a file in " +
                             parent.string() + ": " + errno_text(errno));
  }
  auto fail = [&](int e) {
    ::close(fd);
    ::unlink(tmpl.c_str());
    throw EnvironmentError("cannot write " + given.string() + ": " + errno_text(e));
  };
  for (const std::string_view bytes : parts) {
    size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0) {
        if (errno == EINTR) continue;
        fail(errno);
      }
      done += static_cast<size_t>(n);
    }
  }
  if (::fchmod(fd, 0644) != 0 || ::fsync(fd) != 0) fail(errno);
  if (::close(fd) != 0) {
    const int e = errno;
    ::unlink(tmpl.c_str());
    throw EnvironmentError("cannot write " + given.string() + ": " + errno_text(e));
  }
  if (std::rename(tmpl.c_str(), path.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmpl.c_str());
    throw EnvironmentError("cannot write " + given.string() + ": " + errno_text(e));
  }
}

// ---------------------------------------------------------------------------------------------

OutputSet::~OutputSet() { abort(); }

fs::path OutputSet::add(const std::string& option, const std::string& path) {
  if (done_) throw InternalError("OutputSet::add after commit() or abort()");
  if (path.empty()) throw OutputPathError(option + ": the path is empty");
  const std::string what = option + " " + path;
  const auto refuse = [&](const std::string& rule) { return OutputPathError(what + ": " + rule); };
  const fs::path given(path);
  if (!given.has_filename()) throw refuse("names a directory (ends in '/'), not a file");

  std::string rule;
  const fs::path target = resolve_links(given, rule);
  if (target.empty()) throw refuse(rule);
  rule = target_rule(target);
  if (!rule.empty()) throw refuse(rule);

  // The directory: there, or created (each missing level, remembered for abort()).
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::vector<fs::path> missing;
  for (fs::path d = dir; !d.empty(); d = d.parent_path()) {
    struct stat st;
    if (::stat(d.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode)) throw refuse(d.string() + " is not a directory");
      break;
    }
    if (errno == ENOTDIR) throw refuse("a part of " + d.string() + " is not a directory");
    if (errno != ENOENT) throw refuse("cannot look at " + d.string() + ": " + errno_text(errno));
    missing.push_back(d);
    if (d.parent_path() == d) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) == 0) {
      created_dirs_.push_back(*it);
    } else if (errno != EEXIST) {
      throw refuse("cannot create the directory " + it->string() + ": " + errno_text(errno));
    }
  }

  std::error_code ec;
  const fs::path real_dir = fs::canonical(dir, ec);
  if (ec) throw refuse("cannot look at " + dir.string() + ": " + ec.message());
  const fs::path key = real_dir / target.filename();
  if (const auto it = given_.find(key); it != given_.end()) {
    throw refuse(it->second == what ? "is given twice" : "is the same file as " + it->second);
  }
  Stage& stage = stage_for(what, real_dir);
  const std::string name = given.filename().string();
  if (const auto it = stage.targets.find(name); it != stage.targets.end()) {
    throw refuse("has the same file name in " + real_dir.string() + " as " + it->second.given);
  }
  stage.targets.emplace(name, Target{key, path});
  given_.emplace(key, what);
  return stage.folder / name;
}

OutputSet::Stage& OutputSet::stage_for(const std::string& what, const fs::path& dir) {
  for (Stage& s : stages_)
    if (s.dir == dir) return s;
  Stage s;
  s.dir = dir;
  s.folder = create_watched((dir / ".cutaway.tmp-").string(), RemoveOnSignal::Kind::Folder,
                            s.guard);
  if (s.folder.empty()) {
    throw OutputPathError(what + ": cannot create files in " + dir.string() + ": " +
                          errno_text(errno));
  }
  stages_.push_back(std::move(s));
  return stages_.back();
}

void OutputSet::commit() {
  if (done_) throw InternalError("OutputSet::commit called twice or after abort()");
  struct Move {
    fs::path from, to;
  };
  std::vector<Move> moves;
  try {
    // Every staged file and its target, each target checked again, before any rename.
    for (const Stage& s : stages_) {
      for (const auto& entry : fs::directory_iterator(s.folder)) {
        const std::string name = entry.path().filename().string();
        const auto it = s.targets.find(name);
        fs::path to = it != s.targets.end() ? it->second.path : s.dir / name;  // a companion file
        std::string rule;
        const fs::path resolved = resolve_links(to, rule);
        if (resolved.empty()) throw EnvironmentError("cannot write " + to.string() + ": " + rule);
        rule = target_rule(resolved);
        if (!rule.empty()) throw EnvironmentError("cannot write " + to.string() + ": " + rule);
        moves.push_back({entry.path(), resolved});
      }
    }
  } catch (const fs::filesystem_error& e) {
    abort();
    throw EnvironmentError(std::string("cannot commit the outputs: ") + e.what());
  } catch (...) {
    abort();
    throw;
  }
  // Back to back: the window in which some targets are new and others old is a few renames.
  g_committing.store(1, std::memory_order_release);
  const auto end_commit = [] {
    g_committing.store(0, std::memory_order_release);
    if (const int sig = g_deferred_signal.exchange(0)) ::raise(sig);
  };
  for (size_t i = 0; i < moves.size(); ++i) {
    if (std::rename(moves[i].from.c_str(), moves[i].to.c_str()) != 0) {
      const int e = errno;
      std::string msg = "cannot write " + moves[i].to.string() + ": " + errno_text(e);
      if (i > 0) {
        msg += " (already written:";
        for (size_t j = 0; j < i; ++j) {
          msg += ' ';
          msg += moves[j].to.string();
        }
        msg += ")";
      }
      end_commit();
      abort();
      throw EnvironmentError(msg);
    }
  }
  end_commit();
  std::vector<fs::path> synced;
  for (const Move& m : moves) {
    committed_.push_back(m.to);
    const fs::path d = m.to.parent_path();
    if (std::find(synced.begin(), synced.end(), d) != synced.end()) continue;
    synced.push_back(d);
    const int fd = ::open(d.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
      ::fsync(fd);
      ::close(fd);
    }
  }
  for (Stage& s : stages_) {
    std::error_code ec;
    fs::remove_all(s.folder, ec);
    s.guard.release();
  }
  created_dirs_.clear();  // they hold outputs now
  done_ = true;
}

void OutputSet::abort() noexcept {
  if (done_) return;
  done_ = true;
  for (Stage& s : stages_) {
    std::error_code ec;
    fs::remove_all(s.folder, ec);
    s.guard.release();
  }
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) ::rmdir(it->c_str());
  created_dirs_.clear();
}

std::string OutputSet::describe(std::string message) const {
  const auto replace_all = [&](const std::string& from, const std::string& to) {
    for (size_t at = message.find(from); at != std::string::npos;
         at = message.find(from, at + to.size())) {
      message.replace(at, from.size(), to);
    }
  };
  for (const Stage& s : stages_) {
    // Registered files by the name the user gave, then anything else in the folder (a
    // companion file, a writer's temporary file) by the directory.
    for (const auto& [name, target] : s.targets) {
      replace_all((s.folder / name).string(), target.given);
    }
    replace_all(s.folder.string(), s.dir.string());
  }
  return message;
}

}  // namespace cutaway
