#include "render/povray_runner.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/atomic_file.h"

namespace cutaway {

namespace {

namespace fs = std::filesystem;

constexpr size_t kMaxCaptured = 256 * 1024;  // bytes of POV-Ray's output kept (the tail)
constexpr int kTailLines = 15;               // lines of it quoted in an error

// A fresh directory under the system's temporary directory, removed with everything in it,
// also when SIGTERM, SIGINT or SIGHUP stops the process (RemoveOnSignal).
class TempDir {
 public:
  TempDir() {
    path_ = create_watched((fs::temp_directory_path() / "cutaway-povray-").string(),
                           RemoveOnSignal::Kind::Folder, guard_);
    if (path_.empty()) {
      throw std::runtime_error("cannot create a temporary directory for POV-Ray: " +
                               std::string(std::strerror(errno)));
    }
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  RemoveOnSignal guard_;
};

// Closes a file descriptor when it goes out of scope.
struct Fd {
  int fd = -1;
  ~Fd() { close(); }
  void close() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

// The executable to run: `name` itself when it holds a '/', else the first match in PATH.
// Resolved before fork(), so the child only calls async-signal-safe functions.
std::string find_executable(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) return candidate;
  }
  throw std::runtime_error("'" + name + "' was not found in PATH; install POV-Ray 3.7 "
                           "(scripts/install-deps.sh installs the Debian package povray)");
}

// The last `count` non-empty lines of `text`, joined by newlines.
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

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct ChildResult {
  int status = 0;      // from waitpid
  std::string output;  // stdout and stderr interleaved (the tail of at most kMaxCaptured bytes)
};

// Runs `exe` with `args` (args[0] is the program name) in `dir`, stdin from /dev/null, stdout
// and stderr into one captured pipe. Throws when the program cannot be started.
ChildResult run_in(const fs::path& dir, const std::string& exe,
                   const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string dir_text = dir.string();

  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  Fd out_read{out_pipe[0]}, out_write{out_pipe[1]};
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  Fd exec_read{err_pipe[0]}, exec_write{err_pipe[1]};

  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("cannot fork: ") + std::strerror(errno));
  if (pid == 0) {
    // Child: async-signal-safe calls only. On failure the errno goes to the parent through the
    // close-on-exec pipe (which exec closes on success). POV-Ray gets SIGTERM when the thread
    // that started it ends (the process killed, even by SIGKILL), so no render outlives us.
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

  // A signal that stops us now stops POV-Ray before its folder is swept (RemoveOnSignal).
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
      throw std::runtime_error(std::string("waitpid failed: ") + std::strerror(errno));
    }
  }
  if (got == static_cast<ssize_t>(sizeof child_errno)) {
    throw std::runtime_error("cannot start " + exe + ": " + std::strerror(child_errno) +
                             (child_errno == ENOENT ? " (install POV-Ray 3.7: "
                                                      "scripts/install-deps.sh)"
                                                    : ""));
  }
  return result;
}

}  // namespace

void render_povray(const fs::path& pov_file, const fs::path& png_out, int width, int height,
                   const PovrayOptions& options) {
  if (width < 1 || width > 16384 || height < 1 || height > 16384) {
    throw std::invalid_argument("render_povray: image size " + std::to_string(width) + "x" +
                                std::to_string(height) + " outside 1..16384");
  }
  if (options.quality < 0 || options.quality > 11) {
    throw std::invalid_argument("render_povray: quality " + std::to_string(options.quality) +
                                " outside 0..11");
  }
  if (options.threads < 0) {
    throw std::invalid_argument("render_povray: threads must be >= 0");
  }
  const std::string exe = find_executable(options.executable);
  const std::string scene = read_bytes(pov_file);

  TempDir dir;
  {
    std::ofstream out(dir.path() / "scene.pov", std::ios::binary);
    out << scene;
    if (!out.flush()) {
      throw std::runtime_error("cannot write the scene into " + dir.path().string());
    }
  }

  std::vector<std::string> args = {
      options.executable, "+Iscene.pov", "+Oscene.png", "+FN", "+W" + std::to_string(width),
      "+H" + std::to_string(height), "-D", "-P", "-V", "-GS", "-GR",
      "+Q" + std::to_string(options.quality), "File_Gamma=sRGB"};
  if (options.antialias) {
    args.insert(args.end(), {"+A0.3", "+AM2", "+R3"});
  } else {
    args.push_back("-A");
  }
  if (options.threads > 0) args.push_back("+WT" + std::to_string(options.threads));
  // Files the scene names (image_map textures) are found beside it.
  args.push_back("+L" + fs::absolute(pov_file).parent_path().string());

  const ChildResult run = run_in(dir.path(), exe, args);
  const fs::path image = dir.path() / "scene.png";
  const bool exited_ok = WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0;
  if (!exited_ok || !fs::is_regular_file(image) || fs::file_size(image) == 0) {
    std::string how;
    if (WIFEXITED(run.status)) {
      how = "exited with status " + std::to_string(WEXITSTATUS(run.status));
    } else if (WIFSIGNALED(run.status)) {
      how = "was killed by signal " + std::to_string(WTERMSIG(run.status));
    }
    if (exited_ok) how = "wrote no image";
    throw std::runtime_error("POV-Ray failed on " + pov_file.string() + " (" + how + "):\n" +
                             last_lines(run.output, kTailLines));
  }
  write_file_atomically(png_out, read_bytes(image));
}

}  // namespace cutaway
