#include "base/file_read.h"

#include <cerrno>
#include <cstring>
#include <new>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace cutaway {

FileReadError::FileReadError(const std::filesystem::path& path, std::string rule)
    : EnvironmentError("cannot read " + path.string() + ": " + rule), rule_(std::move(rule)) {}

std::string byte_size_words(uint64_t bytes) {
  if (bytes != 0 && bytes % (uint64_t{1} << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes != 0 && bytes % (uint64_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  if (bytes != 0 && bytes % (uint64_t{1} << 10) == 0) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + " bytes";
}

namespace {

/// The rule of a file over the limit: "is larger than 16 MiB".
std::string larger_than(uint64_t max_bytes) {
  return "is larger than " + byte_size_words(max_bytes);
}

/// Refuses what `st` describes unless it is a regular file of at most max_bytes.
void require_readable(const std::filesystem::path& path, const struct stat& st,
                      uint64_t max_bytes) {
  if (S_ISDIR(st.st_mode)) throw FileReadError(path, "is a directory");
  if (!S_ISREG(st.st_mode))
    throw FileReadError(path, "is not a regular file (a FIFO, socket or device)");
  if (static_cast<uint64_t>(st.st_size) > max_bytes)
    throw FileReadError(path, larger_than(max_bytes));
}

/// The rule for a failed system call: "cannot be read: REASON" (errno's).
std::string system_rule() { return std::string("cannot be read: ") + std::strerror(errno); }

/// Closes a descriptor when it goes out of scope.
struct FdCloser {
  int fd;
  ~FdCloser() { ::close(fd); }
};

}  // namespace

std::string read_regular_file(const std::filesystem::path& path, uint64_t max_bytes) {
  // The path is checked before it is opened (opening some devices has effects of its own),
  // then the descriptor, in case the path was replaced in between.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) throw FileReadError(path, "does not exist");
    throw FileReadError(path, system_rule());
  }
  require_readable(path, st, max_bytes);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw FileReadError(path, system_rule());
  return read_open_file(fd, path, max_bytes);
}

std::string read_open_file(int fd, const std::filesystem::path& path, uint64_t max_bytes) {
  const FdCloser closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw FileReadError(path, system_rule());
  require_readable(path, st, max_bytes);
  std::string bytes;
  try {
    bytes.resize(static_cast<size_t>(st.st_size));  // the one allocation
  } catch (const std::bad_alloc&) {
    throw FileReadError(path, "is too large to hold in memory (" + std::to_string(st.st_size) +
                                  " bytes)");
  }
  size_t got = 0;
  const auto read_into = [&](char* at, size_t n) {
    for (;;) {
      const ssize_t k = ::read(fd, at, n);
      if (k >= 0) return static_cast<size_t>(k);
      if (errno != EINTR) throw FileReadError(path, system_rule());
    }
  };
  while (got < bytes.size()) {
    const size_t k = read_into(bytes.data() + got, bytes.size() - got);
    if (k == 0) break;  // shorter than fstat said: it shrank meanwhile
    got += k;
  }
  bytes.resize(got);
  if (got < static_cast<size_t>(st.st_size)) return bytes;
  // At its size: the end of the file, unless it grew since fstat; then read on, to one byte
  // over the limit at most.
  char more[65536];
  for (;;) {
    const size_t k = read_into(more, sizeof more);
    if (k == 0) return bytes;
    if (bytes.size() + k > max_bytes) throw FileReadError(path, larger_than(max_bytes));
    bytes.append(more, k);
  }
}

}  // namespace cutaway
