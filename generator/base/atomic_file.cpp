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
#include "base/folder.h"

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

fs::path create_watched(const std::string& prefix, RemoveOnSignal::Kind kind, RemoveOnSignal& guard,
                        int* fd, const Folder* in) {
  constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  const int dirfd = in ? in->fd() : AT_FDCWD;
  for (int attempt = 0; attempt < 100; ++attempt) {
    unsigned char random[6];
    if (::getrandom(random, sizeof random, 0) != static_cast<ssize_t>(sizeof random)) return {};
    std::string name = prefix;
    for (const unsigned char r : random) name += kChars[r % (sizeof kChars - 1)];
    const fs::path path = in ? in->path() / name : fs::path(name);
    guard = RemoveOnSignal(path, kind);
    const bool made =
        kind == RemoveOnSignal::Kind::Folder
            ? ::mkdirat(dirfd, name.c_str(), 0700) == 0
            : (*fd = ::openat(dirfd, name.c_str(),
                              O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600)) >= 0;
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
  if (!given.has_filename())
    throw EnvironmentError("cannot write " + given.string() + ": names a folder, not a file");
  Folder folder;
  try {
    folder = Folder::open(given.parent_path(), true);
  } catch (const EnvironmentError& e) {
    throw EnvironmentError("cannot write " + given.string() + ": " + e.what());
  }
  folder.write_atomically(given.filename().string(), parts);
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

  // A link there is replaced, never followed: the given path itself is the target.
  if (const std::string rule = replace_rule(AT_FDCWD, given.string()); !rule.empty())
    throw refuse(rule);

  // The directory: there, or created (each missing level, remembered for abort()).
  const fs::path dir = given.has_parent_path() ? given.parent_path() : fs::path(".");
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
  const fs::path key = real_dir / given.filename();
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
  try {
    s.handle = Folder::open(dir, false);
  } catch (const EnvironmentError& e) {
    throw OutputPathError(what + ": " + e.what());
  }
  s.folder =
      create_watched(".cutaway.tmp-", RemoveOnSignal::Kind::Folder, s.guard, nullptr, &s.handle);
  if (s.folder.empty()) {
    throw OutputPathError(what + ": cannot create files in " + dir.string() + ": " +
                          errno_text(errno));
  }
  try {
    s.staging = s.handle.sub(s.folder.filename().string(), false);
  } catch (const EnvironmentError& e) {
    throw OutputPathError(what + ": " + e.what());
  }
  stages_.push_back(std::move(s));
  return stages_.back();
}

void OutputSet::commit() {
  if (done_) throw InternalError("OutputSet::commit called twice or after abort()");
  struct Move {
    const Stage* stage;
    std::string from, to;  ///< names in the staging folder and in the target's directory
  };
  std::vector<Move> moves;
  try {
    // Every staged file and its target, each target checked again, before any rename.
    for (const Stage& s : stages_) {
      for (const auto& entry : fs::directory_iterator(s.folder)) {
        const std::string name = entry.path().filename().string();
        const auto it = s.targets.find(name);
        const std::string to_name =
            it != s.targets.end() ? it->second.path.filename().string() : name;  // a companion
        const std::string rule = replace_rule(s.handle.fd(), to_name);
        if (!rule.empty())
          throw EnvironmentError("cannot write " + (s.dir / to_name).string() + ": " + rule);
        moves.push_back({&s, name, to_name});
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
    const Move& m = moves[i];
    // Through the directory's handle: a link at the target is replaced, never followed.
    if (::renameat(m.stage->staging.fd(), m.from.c_str(), m.stage->handle.fd(), m.to.c_str()) !=
        0) {
      const int e = errno;
      std::string msg = "cannot write " + (m.stage->dir / m.to).string() + ": " + errno_text(e);
      if (i > 0) {
        msg += " (already written:";
        for (size_t j = 0; j < i; ++j) {
          msg += ' ';
          msg += (moves[j].stage->dir / moves[j].to).string();
        }
        msg += ")";
      }
      end_commit();
      abort();
      throw EnvironmentError(msg);
    }
  }
  end_commit();
  for (const Move& m : moves) committed_.push_back(m.stage->dir / m.to);
  for (const Stage& s : stages_) ::fsync(s.handle.fd());
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
