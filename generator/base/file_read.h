// Reading a file without trusting it: the one way cutaway reads any file (inputs, mesh files,
// manifests, thumbnails, files it wrote). A path that names a FIFO, a device or a socket is
// refused before anything is read from it (a FIFO would block, /dev/zero never ends), the
// size is checked before reading, and no more than the limit is ever read, even from a file
// that grows meanwhile.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "base/error.h"

namespace cutaway {

/// A file that could not be read. what() is "cannot read PATH: RULE"; rule() is the rule alone
/// (e.g. "is larger than 16 MiB"), to follow the file's name in messages that name it their way.
class FileReadError : public EnvironmentError {
 public:
  FileReadError(const std::filesystem::path& path, std::string rule);
  const std::string& rule() const { return rule_; }

 private:
  std::string rule_;
};

/// The bytes of the regular file at `path` (symbolic links followed), at most `max_bytes`.
/// The file is opened without blocking and checked on its open descriptor: a directory, FIFO,
/// socket or device is refused, and so is a file whose size is over `max_bytes`, before any
/// byte is read; at most max_bytes + 1 bytes are read, so a file that grows past the limit
/// while it is read is refused too. Memory: one allocation of the file's size (read_open_file),
/// never more than `max_bytes`.
/// @throws FileReadError whose rule, to follow the file's name, is "does not exist", "is a
///         directory", "is not a regular file (a FIFO, socket or device)", "is larger than N MiB"
///         (KiB, bytes: the largest whole unit of max_bytes) or "cannot be read: REASON"
std::string read_regular_file(const std::filesystem::path& path, uint64_t max_bytes);

/// The bytes of the file open on `fd` (which this takes over and closes), named `path` in
/// errors: checked on the descriptor as read_regular_file checks, then read into one allocation
/// of the file's size until end of file. A file that grows while it is read is read on up to
/// max_bytes + 1 (then refused); only then does the buffer grow. Memory: the file's size.
/// @throws FileReadError as read_regular_file; "is too large to hold in memory (N bytes)" when
///         the allocation fails
std::string read_open_file(int fd, const std::filesystem::path& path, uint64_t max_bytes);

/// `bytes` in words as size rules state it: "16 MiB", "64 KiB", "1000 bytes" (the largest
/// binary unit that divides it).
std::string byte_size_words(uint64_t bytes);

}  // namespace cutaway
