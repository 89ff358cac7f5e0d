// Output files without partial or mixed results (doc/architecture.md, Command line):
//  - write_file_atomically(): one file, written to a temporary file beside the target and
//    renamed into place;
//  - OutputSet: the files of one command, checked before any work, staged in a hidden folder
//    beside each target and renamed into place together at the end (all or none);
//  - RemoveOnSignal: temporary files and folders removed (and the child processes writing into
//    them stopped first) when the process is stopped by SIGTERM, SIGINT or SIGHUP.
// Names of temporary files, for cleaning up after a SIGKILL or a power cut (which nothing can
// catch): "NAME.tmp-XXXXXX" (a file, write_file_atomically()) and ".cutaway.tmp-XXXXXX/" (a
// folder beside the outputs, OutputSet), X being random letters and digits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <sys/types.h>

#include "base/folder.h"

namespace cutaway {

/// Writes `bytes` to `path` atomically, through its folder (Folder::write_atomically,
/// folder.h): a temporary file "NAME.tmp-XXXXXX" made in the folder with O_EXCL | O_NOFOLLOW,
/// flushed (fsync), then renamed over the name. Creates missing parent directories. A symbolic
/// link at `path` is replaced by the file, never written through (the file it pointed to is
/// untouched); a directory, device, FIFO or socket there is refused.
/// The temporary file is removed when the write fails, and by RemoveOnSignal's handlers when
/// SIGTERM, SIGINT or SIGHUP stops the process during the write; after a SIGKILL it stays
/// behind, while `path` keeps its old bytes.
/// @throws EnvironmentError "cannot write PATH: REASON" when the file cannot be written (the
///         temporary file is removed; an existing `path` is unchanged)
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// write_file_atomically of the bytes of `parts` one after the other, without joining them
/// in memory first (a cut cache entry: its payload, then its trailer).
/// @throws EnvironmentError as write_file_atomically
void write_file_atomically(const std::filesystem::path& path,
                           std::span<const std::string_view> parts);

/// The largest file the program reads back (a glTF binary's own limit, 4 GiB).
inline constexpr uint64_t kMaxReadBackBytes = uint64_t{4} << 30;

/// The bytes of the file at `path` (what write_file_atomically wrote, or any file the program
/// reads back: POV-Ray's image, manifests, thumbnails), through read_regular_file (file_read.h)
/// with the limit kMaxReadBackBytes.
/// @throws FileReadError (an EnvironmentError) "cannot read PATH: REASON" when it is not a
///         regular file, is larger than the limit, or cannot be opened or read
std::string read_file_bytes(const std::filesystem::path& path);

/// Removes a temporary file, or a folder with the files directly in it, when the process is
/// stopped by SIGTERM, SIGINT or SIGHUP while the guard lives; or stops a child process that
/// writes into such a folder (SIGKILL, then reaped) before any file is removed, so that it
/// cannot add a file after the folder was emptied. The destructor only stops watching (it
/// removes and stops nothing).
///
/// The handlers are installed on first use, for those of the three signals whose action is
/// still the default (a signal the process ignores, e.g. SIGHUP under nohup, stays ignored; a
/// handler of the program's own stays). They use only system calls (unlink, unlinkat, rmdir,
/// open, lseek, getdents64, close, kill, waitpid, sigaction, raise) and then raise the signal
/// again with its default action, so the process still ends "killed by signal N". At most 128
/// paths and child processes are watched at a time; beyond that one is simply not watched (it
/// still works, without the cleanup).
/// Thread-safe.
class RemoveOnSignal {
 public:
  enum class Kind { File, Folder };
  RemoveOnSignal() = default;
  /// Watches `path` (made absolute, at most PATH_MAX - 1 bytes; longer ones are not watched).
  explicit RemoveOnSignal(const std::filesystem::path& path, Kind kind = Kind::File);
  /// Watches the child process `child` (> 0, started by this process and not reaped yet).
  explicit RemoveOnSignal(pid_t child);
  ~RemoveOnSignal();
  RemoveOnSignal(RemoveOnSignal&& other) noexcept;
  RemoveOnSignal& operator=(RemoveOnSignal&& other) noexcept;
  RemoveOnSignal(const RemoveOnSignal&) = delete;
  RemoveOnSignal& operator=(const RemoveOnSignal&) = delete;
  /// Stops watching now.
  void release() noexcept;

 private:
  int slot_ = -1;
};

/// Creates a new file (mode 0600, open for writing, its descriptor in *fd) or folder (mode
/// 0700, fd null) named `prefix` followed by six random letters and digits, as mkstemp and
/// mkdtemp do, but watched by `guard` from before it exists: no signal can find it created and
/// not yet watched. With `in`, `prefix` is a plain name in that folder and the file or folder
/// is made through its handle (openat with O_EXCL | O_NOFOLLOW, mkdirat).
/// @returns its path, or an empty path with errno set when it cannot be created
std::filesystem::path create_watched(const std::string& prefix, RemoveOnSignal::Kind kind,
                                     RemoveOnSignal& guard, int* fd = nullptr,
                                     const Folder* in = nullptr);

/// An output path refused before any work: what() is "OPTION PATH: RULE", e.g.
/// "--png out/x.png: is a directory", or "-o: the path is empty". The CLI reports it as bad
/// input (exit code 2).
class OutputPathError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// The output files of one command, written all or none.
///
/// Every output is registered with add() before any work starts; add() checks the path and
/// returns where to write it instead: a file of the same name in a fresh hidden folder
/// ".cutaway.tmp-XXXXXX" in the target's directory (one per directory). Writers write there
/// (any writer: companion files they put beside it, e.g. the .bin of a .gltf, are staged
/// too). commit() then renames every staged file onto its target, back to back at the very
/// end; abort() (or the destructor, without commit()) removes everything staged and every
/// directory add() created, so no target changes. The staging folders are watched by
/// RemoveOnSignal, so SIGTERM, SIGINT or SIGHUP removes them too; after a SIGKILL a
/// ".cutaway.tmp-XXXXXX" folder stays behind, and every target has its old bytes or its new
/// ones, never part of a file.
///
/// Renames of several files cannot be one atomic operation: a crash during commit() (a few
/// rename() calls, microseconds) can still leave some targets new and others old, and a
/// rename that fails there (rare: the targets were checked just before) leaves the earlier
/// ones in place (the error says which). Two processes writing the same target leave one
/// complete file, the last one renamed.
///
/// Rules add() applies to a path (each refusal an OutputPathError "OPTION PATH: RULE"):
///  - not empty, and not ending in '/';
///  - a symbolic link at the path is replaced by the file, never written through: the file it
///    points to is untouched (commit() renames through the directory's handle, renameat);
///  - an existing target must be a regular file or a link: a directory, a character or block
///    device (/dev/null and /dev/full included), a FIFO or a socket is refused ("is not a
///    regular file");
///  - the target's directory is created when missing (with its missing parents; abort()
///    removes them again), unless some part of it exists and is not a directory;
///  - the directory must let us create files (the staging folder is created there, so a
///    read-only file system or missing permission is found here, not after the work);
///  - no two outputs may have the same target (the same name in the same directory).
/// Not thread-safe: one thread registers, writes and commits.
class OutputSet {
 public:
  OutputSet() = default;
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Registers output `path`, given by command-line option `option` (named in errors), and
  /// returns the path to write it to (in a staging folder; the same file name).
  /// @throws OutputPathError when the path breaks one of the rules above
  std::filesystem::path add(const std::string& option, const std::string& path);

  /// Renames every staged file onto its target (a registered output that was never written
  /// stays as it was), syncs the directories and removes the staging folders. Call once, after
  /// all writes succeeded. On failure everything not yet renamed is removed.
  /// @throws EnvironmentError "cannot write TARGET: REASON" when a target became a directory
  ///         or another non-regular file since add(), or a rename fails
  void commit();

  /// The files commit() renamed into place (registered outputs and their companion files,
  /// such as a .gltf's .bin or a .pov's textures), absolute, in rename order; empty before.
  const std::vector<std::filesystem::path>& committed() const { return committed_; }

  /// Removes everything staged and the directories add() created (those still empty). Safe to
  /// call more than once, and after commit() (then it does nothing).
  void abort() noexcept;

  /// `message` with every staging path in it replaced by the target's directory, so that an
  /// error of a writer names the file the user asked for.
  std::string describe(std::string message) const;

 private:
  struct Target {
    std::filesystem::path path;  ///< where the file goes (its directory resolved, absolute)
    std::string given;           ///< the path as the user gave it
  };
  struct Stage {
    std::filesystem::path dir;              ///< the targets' directory (resolved, absolute)
    Folder handle;                          ///< `dir`, open: targets are renamed through it
    std::filesystem::path folder;           ///< the staging folder in it
    Folder staging;                         ///< `folder`, open
    std::map<std::string, Target> targets;  ///< staged file name -> its target
    RemoveOnSignal guard;
  };
  /// The stage of directory `dir`, its staging folder created on first use.
  /// @throws OutputPathError "WHAT: cannot create files in DIR: REASON"
  Stage& stage_for(const std::string& what, const std::filesystem::path& dir);

  std::vector<Stage> stages_;
  std::map<std::filesystem::path, std::string> given_;  ///< target -> "OPTION PATH"
  std::vector<std::filesystem::path> created_dirs_;     ///< by add(), in creation order
  std::vector<std::filesystem::path> committed_;        ///< by commit(), in rename order
  bool done_ = false;
};

}  // namespace cutaway
