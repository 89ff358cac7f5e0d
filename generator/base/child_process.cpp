#include "base/child_process.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "base/error.h"

namespace cutaway {

namespace {

namespace fs = std::filesystem;

constexpr size_t kMaxCaptured = 256 * 1024;  // bytes of the child's output kept (the tail)

// Closes a file descriptor when it goes out of scope.
struct Fd {
  int fd = -1;
  ~Fd() { close(); }
  void close() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

}  // namespace

std::string find_executable(const std::string& name, const std::string& hint) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) return candidate;
  }
  throw EnvironmentError("'" + name + "' was not found in PATH; " + hint);
}

ChildResult run_child(const fs::path& dir, const std::string& exe,
                      const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string dir_text = dir.string();

  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) {
    throw EnvironmentError(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  Fd out_read{out_pipe[0]}, out_write{out_pipe[1]};
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    throw EnvironmentError(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  Fd exec_read{err_pipe[0]}, exec_write{err_pipe[1]};

  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw EnvironmentError(std::string("cannot fork: ") + std::strerror(errno));
  if (pid == 0) {
    // Child: async-signal-safe calls only. On failure the errno goes to the parent through the
    // close-on-exec pipe (which exec closes on success). The child gets SIGTERM when the thread
    // that started it ends (the process killed, even by SIGKILL), so no child outlives us.
    int err = 0;
    if (::prctl(PR_SET_PDEATHSIG, SIGTERM) != 0 || ::getppid() != parent) ::_exit(127);
    const int null_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (null_fd < 0 || ::dup2(null_fd, 0) < 0 || ::dup2(out_pipe[1], 1) < 0 ||
        ::dup2(out_pipe[1], 2) < 0 || ::chdir(dir_text.c_str()) != 0) {
      err = errno;
    } else {
      ::execv(exe.c_str(), argv.data());
      err = errno;
    }
    const ssize_t ignored = ::write(err_pipe[1], &err, sizeof err);
    (void)ignored;
    ::_exit(127);
  }

  // A signal that stops us now stops the child first (RemoveOnSignal).
  RemoveOnSignal stop_child(pid);
  out_write.close();
  exec_write.close();
  ChildResult result;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(out_read.fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    result.output.append(buf, static_cast<size_t>(n));
    if (result.output.size() > 2 * kMaxCaptured) {
      result.output.erase(0, result.output.size() - kMaxCaptured);
    }
  }
  int child_errno = 0;
  ssize_t got;
  do {
    got = ::read(exec_read.fd, &child_errno, sizeof child_errno);
  } while (got < 0 && errno == EINTR);
  // Wait for its end without reaping it, stop watching, then reap: the watched process id is
  // never one the system could have given to another process.
  siginfo_t info;
  while (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
  }
  stop_child.release();
  while (::waitpid(pid, &result.status, 0) < 0) {
    if (errno != EINTR) {
      throw EnvironmentError(std::string("waitpid failed: ") + std::strerror(errno));
    }
  }
  if (got == static_cast<ssize_t>(sizeof child_errno)) {
    throw EnvironmentError("cannot start " + exe + ": " + std::strerror(child_errno));
  }
  return result;
}

TempDir::TempDir(const std::string& prefix) {
  path_ = create_watched((std::filesystem::temp_directory_path() / prefix).string(),
                         RemoveOnSignal::Kind::Folder, guard_);
  if (path_.empty())
    throw EnvironmentError("cannot create a temporary folder " + prefix +
                           "XXXXXX: " + std::string(std::strerror(errno)));
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::string last_lines(const std::string& text, int count) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) lines.push_back(line);
  }
  const size_t first = lines.size() > static_cast<size_t>(count) ? lines.size() - count : 0;
  std::string out;
  for (size_t i = first; i < lines.size(); ++i) out += (i > first ? "\n" : "") + lines[i];
  return out;
}

}  // namespace cutaway
