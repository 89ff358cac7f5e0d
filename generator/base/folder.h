// Writing into a folder through its handle (doc/command-line.md, Outputs and links): the one way
// cutaway creates, replaces and removes files. A folder is opened once (open(2) with
// O_DIRECTORY); every file in it is then made with openat(2) and renamed into place with
// renameat(2) relative to that handle, never by a path that a link could redirect:
//  - a symbolic link at a destination is replaced by the new file (the link goes, the file it
//    pointed to is untouched); nothing is ever written through a link;
//  - temporary files are created with O_CREAT | O_EXCL | O_NOFOLLOW, so a name planted in
//    advance (a link, a FIFO) makes the creation fail instead of being followed;
//  - sub-folders inside the opened folder (a cache's shards) are opened with O_NOFOLLOW, so a
//    link planted in their place is refused instead of leading outside;
//  - a directory, device, FIFO or socket at a destination is refused (never replaced).
// The folder itself is opened by the path the caller gives, links in that path followed: the
// user named it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <sys/types.h>

namespace cutaway {

/// What lies at a name in a folder, looked at without following a link (fstatat with
/// AT_SYMLINK_NOFOLLOW).
enum class EntryKind { Missing, Regular, Link, Directory, Special };

/// An open folder (a directory file descriptor), closed when the last copy goes.
class Folder {
 public:
  Folder() = default;

  /// Opens the folder at `path` (links in `path` followed), first creating it and its missing
  /// parents (mode 0777 less the umask) when `create`.
  /// @throws EnvironmentError "cannot open the folder PATH: REASON" ("is not a folder" when it is
  ///         a file), or "cannot create the folder PATH: REASON"
  static Folder open(const std::filesystem::path& path, bool create);

  /// The sub-folder `name` (one plain name: no '/', not "." or "..") of this folder, opened
  /// with O_NOFOLLOW: a symbolic link there is refused ("is a symbolic link, not a folder").
  /// Created (mkdirat, `mode` less the umask) when missing and `create`.
  /// @throws EnvironmentError "cannot open the folder PATH/NAME: REASON"
  Folder sub(std::string_view name, bool create, mode_t mode = 0777) const;

  /// What lies at `name` in this folder, without following a link.
  EntryKind kind(std::string_view name) const;

  /// Writes the bytes of `parts`, one after the other, to `name` in this folder atomically: a
  /// temporary file "NAME.tmp-XXXXXX" made with O_CREAT | O_EXCL | O_NOFOLLOW (mode 0600 until
  /// written, then `mode`), flushed (fsync), renamed onto `name` (renameat). A symbolic link
  /// at `name` is replaced, never followed. The temporary file is removed when the write fails
  /// and watched by RemoveOnSignal (atomic_file.h) while it exists.
  /// @throws EnvironmentError "cannot write PATH/NAME: REASON"; "is a directory" or "is not a
  ///         regular file (a device, FIFO or socket)..." when such a thing is at `name` (it is
  ///         left as it is)
  void write_atomically(std::string_view name, std::span<const std::string_view> parts,
                        mode_t mode = 0644) const;

  /// The bytes of the regular file `name` in this folder, opened with O_NOFOLLOW and checked on
  /// its descriptor as read_regular_file (file_read.h) does: at most `max_bytes`, one
  /// allocation of the file's size.
  /// @throws FileReadError "cannot read PATH/NAME: RULE", the rule "is a symbolic link" for a
  ///         link
  std::string read(std::string_view name, uint64_t max_bytes) const;

  /// A descriptor (the caller closes it) of the regular file `name` in this folder, opened
  /// read-only with O_NOFOLLOW and O_NONBLOCK and checked on the descriptor.
  /// @throws FileReadError "cannot read PATH/NAME: RULE": "does not exist", "is a symbolic
  ///         link", "is a directory", "is not a regular file (a FIFO, socket or device)"
  int open_regular(std::string_view name) const;

  /// Removes the file (or link, FIFO...) `name` in this folder (unlinkat; a link itself, not its
  /// target). Returns whether something was removed.
  bool remove(std::string_view name) const noexcept;

  /// The plain names of the entries in this folder ("." and ".." left out), in no order.
  /// @throws EnvironmentError "cannot list the folder PATH: REASON"
  std::vector<std::string> names() const;

  int fd() const;
  const std::filesystem::path& path() const { return path_; }
  explicit operator bool() const { return static_cast<bool>(fd_); }

 private:
  Folder(std::shared_ptr<const int> fd, std::filesystem::path path)
      : fd_(std::move(fd)), path_(std::move(path)) {}
  std::shared_ptr<const int> fd_;
  std::filesystem::path path_;
};

/// "" when what lies at `name` in the folder `dirfd` (or at the path `name` with AT_FDCWD),
/// looked at without following a link, may be replaced by a regular file: nothing, a regular
/// file or a symbolic link (replaced itself). Else the rule it breaks: "is a directory", or "is
/// not a regular file (a device, FIFO or socket); outputs must be regular files".
std::string replace_rule(int dirfd, const std::string& name);

/// Whether `name` is one plain file name: not empty, not "." or "..", no '/' and no NUL.
bool plain_name(std::string_view name);

}  // namespace cutaway
