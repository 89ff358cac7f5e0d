#include "base/folder.h"

#include <cerrno>
#include <cstring>
#include <vector>

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/file_read.h"

namespace cutaway {

namespace fs = std::filesystem;

namespace {

std::string errno_words(int e) { return std::strerror(e); }

/// A descriptor shared by the copies of a Folder, closed with the last.
std::shared_ptr<const int> own_fd(int fd) {
  return std::shared_ptr<const int>(new int(fd), [](const int* p) {
    ::close(*p);
    delete p;
  });
}

}  // namespace

std::string replace_rule(int dirfd, const std::string& name) {
  struct stat st;
  if (::fstatat(dirfd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) return "";
  if (S_ISDIR(st.st_mode)) return "is a directory";
  if (!S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode))
    return "is not a regular file (a device, FIFO or socket); outputs must be regular files";
  return "";
}

bool plain_name(std::string_view name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string_view::npos &&
         name.find('\0') == std::string_view::npos;
}

int Folder::fd() const {
  if (!fd_) throw InternalError("Folder: not open");
  return *fd_;
}

Folder Folder::open(const fs::path& path, bool create) {
  const fs::path where = path.empty() ? fs::path(".") : path;
  if (create) {
    std::error_code ec;
    fs::create_directories(where, ec);
    if (ec && !fs::is_directory(where))
      throw EnvironmentError("cannot create the folder " + where.string() + ": " + ec.message());
  }
  const int fd = ::open(where.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    const int e = errno;
    throw EnvironmentError("cannot open the folder " + where.string() + ": " +
                           (e == ENOTDIR ? std::string("is not a folder") : errno_words(e)));
  }
  return Folder(own_fd(fd), path);  // named as given: messages show the user's path
}

Folder Folder::sub(std::string_view name, bool create, mode_t mode) const {
  const std::string n(name);
  const fs::path shown = path_ / n;
  if (!plain_name(name)) throw InternalError("Folder::sub: not a plain name: " + n);
  if (create && ::mkdirat(fd(), n.c_str(), mode) != 0 && errno != EEXIST)
    throw EnvironmentError("cannot create the folder " + shown.string() + ": " +
                           errno_words(errno));
  const int sub_fd = ::openat(fd(), n.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (sub_fd < 0) {
    const int e = errno;
    std::string rule = errno_words(e);
    if (e == ELOOP) rule = "is a symbolic link, not a folder";
    if (e == ENOTDIR)
      rule = kind(name) == EntryKind::Link ? "is a symbolic link, not a folder" : "is not a folder";
    throw EnvironmentError("cannot open the folder " + shown.string() + ": " + rule);
  }
  return Folder(own_fd(sub_fd), shown);
}

EntryKind Folder::kind(std::string_view name) const {
  struct stat st;
  if (::fstatat(fd(), std::string(name).c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0)
    return EntryKind::Missing;
  if (S_ISREG(st.st_mode)) return EntryKind::Regular;
  if (S_ISLNK(st.st_mode)) return EntryKind::Link;
  if (S_ISDIR(st.st_mode)) return EntryKind::Directory;
  return EntryKind::Special;
}

void Folder::write_atomically(std::string_view name, std::span<const std::string_view> parts,
                              mode_t mode) const {
  const std::string n(name);
  const std::string shown = (path_ / n).string();
  if (!plain_name(name)) throw InternalError("Folder::write_atomically: not a plain name: " + n);
  const std::string rule = replace_rule(fd(), n);
  if (!rule.empty()) throw EnvironmentError("cannot write " + shown + ": " + rule);
  RemoveOnSignal guard;
  int out = -1;
  const fs::path tmp = create_watched(n + ".tmp-", RemoveOnSignal::Kind::File, guard, &out, this);
  if (tmp.empty())
    throw EnvironmentError("cannot write " + shown + ": cannot create a file in " + path_.string() +
                           ": " + errno_words(errno));
  const std::string tmp_name = tmp.filename().string();
  const auto fail = [&](int e) {
    if (out >= 0) ::close(out);
    ::unlinkat(fd(), tmp_name.c_str(), 0);
    throw EnvironmentError("cannot write " + shown + ": " + errno_words(e));
  };
  for (const std::string_view bytes : parts) {
    size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t k = ::write(out, bytes.data() + done, bytes.size() - done);
      if (k < 0) {
        if (errno == EINTR) continue;
        fail(errno);
      }
      done += static_cast<size_t>(k);
    }
  }
  if (::fchmod(out, mode) != 0 || ::fsync(out) != 0) fail(errno);
  const int closed = ::close(out);
  out = -1;
  if (closed != 0) fail(errno);
  // renameat replaces a link or file at `name` by the new file; it never follows the link.
  if (::renameat(fd(), tmp_name.c_str(), fd(), n.c_str()) != 0) {
    const int e = errno;
    if (e == EISDIR || e == ENOTEMPTY || e == EEXIST) {
      ::unlinkat(fd(), tmp_name.c_str(), 0);
      throw EnvironmentError("cannot write " + shown + ": is a directory");
    }
    fail(e);
  }
}

int Folder::open_regular(std::string_view name) const {
  const fs::path shown = path_ / std::string(name);
  const int in = ::openat(fd(), std::string(name).c_str(),
                          O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC);
  if (in < 0) {
    const int e = errno;
    if (e == ENOENT) throw FileReadError(shown, "does not exist");
    if (e == ELOOP) throw FileReadError(shown, "is a symbolic link");
    throw FileReadError(shown, "cannot be read: " + errno_words(e));
  }
  struct stat st;
  if (::fstat(in, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(in);
    throw FileReadError(shown, S_ISDIR(st.st_mode)
                                   ? "is a directory"
                                   : "is not a regular file (a FIFO, socket or device)");
  }
  return in;
}

std::string Folder::read(std::string_view name, uint64_t max_bytes) const {
  return read_open_file(open_regular(name), path_ / std::string(name), max_bytes);
}

bool Folder::remove(std::string_view name) const noexcept {
  if (!fd_) return false;
  const std::string n(name);
  return ::unlinkat(*fd_, n.c_str(), 0) == 0 || ::unlinkat(*fd_, n.c_str(), AT_REMOVEDIR) == 0;
}

std::vector<std::string> Folder::names() const {
  const int dup_fd = ::openat(fd(), ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  DIR* dir = dup_fd >= 0 ? ::fdopendir(dup_fd) : nullptr;
  if (!dir) {
    const int e = errno;
    if (dup_fd >= 0) ::close(dup_fd);
    throw EnvironmentError("cannot list the folder " + path_.string() + ": " + errno_words(e));
  }
  std::vector<std::string> out;
  while (const dirent* d = ::readdir(dir)) {
    const std::string_view n = d->d_name;
    if (n != "." && n != "..") out.emplace_back(n);
  }
  ::closedir(dir);
  return out;
}

}  // namespace cutaway
