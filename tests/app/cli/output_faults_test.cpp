// Output faults: whatever goes wrong, the CLI never leaves a partial file or a mix of new and
// old outputs (generator/base/atomic_file.h, OutputSet). Runs of `cutaway` stopped by SIGTERM,
// SIGINT, SIGHUP (nothing temporary left, the old outputs whole) and SIGKILL (the old outputs
// whole); a failure after some outputs were written (none changes); paths refused before any
// work with exit code 2 (unwritable, a device, a FIFO, a directory, empty, given twice);
// missing directories (created, and removed again when the run fails); symbolic links (replaced,
// never written through); a write error (exit code 1, no partial file); two writers of one file.
//
// The tests run as root, where permission bits do not stop a write; an unwritable place is
// therefore a path below a regular file (the directory cannot be created), and the write error
// comes from RLIMIT_FSIZE (writes past the limit fail with EFBIG), not from a full disk. The
// permission case (chmod 0555) runs only when the tests do not run as root.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <thread>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

const char* kScene = "tests/data/scenes/halved_tomato.yaml";  // ~0.5 s, then ~1.5 s POV-Ray
const char* kTomato = "templates/tomato.yaml";

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// Every entry directly in `dir` (hidden ones and folders too), sorted.
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// The staging folders (".cutaway.tmp-XXXXXX") in `dir`.
std::vector<fs::path> staging_folders(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(".cutaway.tmp-", 0) == 0) out.push_back(e.path());
  return out;
}

/// How a child process is started.
struct Spawn {
  std::vector<std::string> args;
  rlim_t file_size_limit = RLIM_INFINITY;  ///< RLIMIT_FSIZE (SIGXFSZ ignored, so writes fail)
  std::vector<std::string> env;            ///< NAME=VALUE set in the child
};

/// A running `cutaway`, in the source directory, stdout and stderr into `log`.
struct Child {
  pid_t pid = -1;
  fs::path log;
};

Child start(const Spawn& s, const fs::path& log) {
  std::vector<std::string> argv_text = {CUTAWAY_BINARY};
  argv_text.insert(argv_text.end(), s.args.begin(), s.args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env = s.env;
  const pid_t pid = ::fork();
  if (pid == 0) {
    // The signal actions and mask this process was started with (a background job ignores
    // SIGINT) must not leak into the test.
    for (int sig : {SIGTERM, SIGINT, SIGHUP}) std::signal(sig, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    if (s.file_size_limit != RLIM_INFINITY) {
      std::signal(SIGXFSZ, SIG_IGN);
      const rlimit lim{s.file_size_limit, s.file_size_limit};
      ::setrlimit(RLIMIT_FSIZE, &lim);
    }
    for (std::string& e : env) ::putenv(e.data());
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || ::dup2(fd, 1) < 0 || ::dup2(fd, 2) < 0 || ::chdir(CUTAWAY_SOURCE_DIR) != 0)
      ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return {pid, log};
}

/// Waits for `c` and returns its wait status.
int wait_for(const Child& c) {
  int status = 0;
  while (::waitpid(c.pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

/// Runs `s` to the end: exit code (128 + N when killed by signal N) and what it printed.
test::RunResult run(const Spawn& s, const fs::path& log) {
  const int status = wait_for(start(s, log));
  test::RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = test::read_file(log);
  fs::remove(log);
  return r;
}

/// True once `ready` holds, polled every millisecond; false when the child ended first. No
/// deadline: the run ends by itself within seconds, and a hang is CTest's timeout to catch.
template <class Ready>
bool wait_until(const Child& c, Ready ready) {
  for (;;) {
    if (ready()) return true;
    int status;
    if (::waitpid(c.pid, &status, WNOHANG) == c.pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

/// The folder `dir`-tmpdir, made empty: TMPDIR of a run writing into `dir` (POV-Ray's
/// temporary folder goes there, so the tests see it removed).
fs::path tmpdir_of(const fs::path& dir) {
  const fs::path t = dir.parent_path() / (dir.filename().string() + "-tmpdir");
  fs::remove_all(t);
  fs::create_directories(t);
  return t;
}

/// A scene run writing a.glb, a.pov and a.png (POV-Ray) into `dir`, TMPDIR `tmpdir`.
Spawn scene_run(const fs::path& dir, const fs::path& tmpdir) {
  Spawn s;
  s.args = {"scene",
            kScene,
            "--backend",
            "cpu",
            "--cube",
            "4",
            "-q",
            "-o",
            (dir / "a.glb").string(),
            "-o",
            (dir / "a.pov").string(),
            "--render",
            (dir / "a.png").string()};
  s.env = {"TMPDIR=" + tmpdir.string()};
  return s;
}

/// Old outputs of an earlier run, to be kept whole.
void write_old_outputs(const fs::path& dir) {
  write_text(dir / "a.glb", "old glb");
  write_text(dir / "a.pov", "old pov");
  write_text(dir / "a.png", "old png");
}

void expect_old_outputs(const fs::path& dir) {
  EXPECT_EQ(test::read_file(dir / "a.glb"), "old glb");
  EXPECT_EQ(test::read_file(dir / "a.pov"), "old pov");
  EXPECT_EQ(test::read_file(dir / "a.png"), "old png");
}

/// Where the run is when the signal comes.
enum class When { WritingPov, Rendering };

/// Starts the scene run, waits until it is at `when` in its staging folder, sends `sig`.
/// Returns the wait status.
int kill_scene_run(const fs::path& dir, const fs::path& tmpdir, int sig, When when) {
  const Child c =
      start(scene_run(dir, tmpdir), dir.parent_path() / (dir.filename().string() + ".log"));
  const bool reached = wait_until(c, [&] {
    for (const fs::path& f : staging_folders(dir)) {
      std::error_code ec;
      for (const auto& e : fs::directory_iterator(f, ec)) {
        const std::string name = e.path().filename().string();
        // a.pov.tmp-XXXXXX while the .pov is written; a.pov once it is (POV-Ray then runs).
        if (name == "a.pov" || (when == When::WritingPov && name.rfind("a.pov.tmp-", 0) == 0))
          return true;
      }
    }
    return false;
  });
  ::kill(c.pid, reached ? sig : SIGKILL);
  const int status = wait_for(c);
  const std::string log = test::read_file(c.log);
  fs::remove(c.log);
  EXPECT_TRUE(reached) << "the run ended before its outputs were staged:\n" << log;
  return status;
}

class SignalMidRun : public ::testing::TestWithParam<std::pair<int, When>> {};

TEST_P(SignalMidRun, RemovesEveryTemporaryFileAndKeepsTheOldOutputs) {
  const auto [sig, when] = GetParam();
  const fs::path dir = test::fresh_dir("output_faults_signal");
  write_old_outputs(dir);
  const fs::path tmpdir = tmpdir_of(dir);
  const int status = kill_scene_run(dir, tmpdir, sig, when);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), sig) << "the exit status must still say: killed by the signal";
  // No staging folder, no NAME.tmp-XXXXXX: exactly the old files; POV-Ray's folder is gone.
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"a.glb", "a.png", "a.pov"}));
  expect_old_outputs(dir);
  EXPECT_TRUE(entries(tmpdir).empty());
  fs::remove_all(tmpdir);
}

INSTANTIATE_TEST_SUITE_P(OutputFaults, SignalMidRun,
                         ::testing::Values(std::make_pair(SIGTERM, When::WritingPov),
                                           std::make_pair(SIGTERM, When::Rendering),
                                           std::make_pair(SIGINT, When::Rendering),
                                           std::make_pair(SIGHUP, When::WritingPov)),
                         [](const ::testing::TestParamInfo<std::pair<int, When>>& info) {
                           const int sig = info.param.first;
                           return std::string(sig == SIGTERM  ? "SIGTERM"
                                              : sig == SIGINT ? "SIGINT"
                                                              : "SIGHUP") +
                                  (info.param.second == When::WritingPov ? "_WritingPov"
                                                                         : "_Rendering");
                         });

TEST(OutputFaults, SigkillKeepsTheOldOutputsWhole) {
  const fs::path dir = test::fresh_dir("output_faults_sigkill");
  write_old_outputs(dir);
  const fs::path tmpdir = tmpdir_of(dir);
  const int status = kill_scene_run(dir, tmpdir, SIGKILL, When::Rendering);
  fs::remove_all(tmpdir);  // POV-Ray's folder stays behind too
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  expect_old_outputs(dir);
  // SIGKILL cannot be caught: the staging folder stays, under its documented name, and
  // nothing else is new.
  const std::vector<fs::path> left = staging_folders(dir);
  EXPECT_EQ(left.size(), 1u);
  EXPECT_EQ(entries(dir).size(), 3u + left.size());
}

TEST(OutputFaults, AFailureAfterSomeOutputsWereWrittenChangesNone) {
  // No POV-Ray in PATH: a.glb and a.pov are written, then --render fails.
  const fs::path dir = test::fresh_dir("output_faults_late_failure");
  write_old_outputs(dir);
  const fs::path tmpdir = tmpdir_of(dir);
  Spawn s = scene_run(dir, tmpdir);
  s.env.push_back("PATH=/nonexistent");
  const test::RunResult r = run(s, dir.parent_path() / (dir.filename().string() + ".log"));
  fs::remove_all(tmpdir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("not found in PATH"), std::string::npos) << r.err;
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"a.glb", "a.png", "a.pov"}));
  expect_old_outputs(dir);
}

TEST(OutputFaults, AnUnwritablePathIsRefusedBeforeAnyWork) {
  const fs::path dir = test::fresh_dir("output_faults_unwritable");
  write_text(dir / "file", "a regular file");
  // --png below a regular file: its directory can neither exist nor be created.
  const test::RunResult r = test::run_cutaway({"model", kTomato, "-o", (dir / "ok.glb").string(),
                                               "--png", (dir / "file" / "x.png").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("cutaway: --png " + (dir / "file" / "x.png").string() + ": "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("is not a directory"), std::string::npos) << r.err;
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"file"}));  // no ok.glb

  // The same for a folder of `variants`, and (not as root) a directory without write permission.
  const test::RunResult v =
      test::run_cutaway({"variants", kTomato, "--count", "2", "-o", (dir / "file").string()});
  EXPECT_EQ(v.exit_code, 2) << v.err;
  EXPECT_NE(v.err.find("is not a directory"), std::string::npos) << v.err;
  if (::geteuid() != 0) {
    fs::create_directory(dir / "ro");
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    const test::RunResult p = test::run_cutaway(
        {"model", kTomato, "-o", (dir / "ok.glb").string(), "--png", (dir / "ro/x.png").string()});
    fs::permissions(dir / "ro", fs::perms::owner_all);
    EXPECT_EQ(p.exit_code, 2) << p.err;
    EXPECT_NE(p.err.find("cannot create files in"), std::string::npos) << p.err;
  }
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"file"})) << "no ok.glb";
}

TEST(OutputFaults, AWriteErrorIsExitCode1AndLeavesNoPartialFile) {
  const fs::path dir = test::fresh_dir("output_faults_write_error");
  write_text(dir / "x.glb", "old glb");
  Spawn s;
  s.args = {"model", kTomato, "-q", "-o", (dir / "x.glb").string()};
  s.file_size_limit = 64 * 1024;  // the glb is over a megabyte
  const test::RunResult r = run(s, dir.parent_path() / (dir.filename().string() + ".log"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  // The message names the file asked for, not the staging folder.
  EXPECT_NE(r.err.find("cutaway: error: cannot write " + (dir / "x.glb").string() + ": "),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find(".cutaway.tmp-"), std::string::npos) << r.err;
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"x.glb"}));
  EXPECT_EQ(test::read_file(dir / "x.glb"), "old glb");
}

// A device, FIFO or folder named as an output is refused before any work; a link to a device
// is replaced by the output (the device is never written).
TEST(OutputFaults, DevicesAndFifosAreRefusedAndLinksToThemReplaced) {
  const fs::path dir = test::fresh_dir("output_faults_devices");
  fs::create_symlink("/dev/null", dir / "null.glb");
  fs::create_symlink("/dev/full", dir / "full.png");
  ASSERT_EQ(::mkfifo((dir / "fifo.pov").c_str(), 0644), 0);
  fs::create_directory(dir / "folder.glb");
  std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"piece", kTomato, "--cut", "halves", "-o", (dir / "fifo.pov").string()},
       "-o " + (dir / "fifo.pov").string()},
      {{"model", kTomato, "-o", (dir / "folder.glb").string()},
       "-o " + (dir / "folder.glb").string()},
      {{"sheet", kTomato, "-o", "/dev/full/x.png"}, "-o /dev/full/x.png"},
  };
  // A character device of our own (root makes one: a second /dev/zero), refused by kind.
  const bool device = ::mknod((dir / "zero.png").c_str(), S_IFCHR | 0666, makedev(1, 5)) == 0;
  if (device)
    cases.push_back(
        {{"model", kTomato, "-o", (dir / "ok.glb").string(), "--png", (dir / "zero.png").string()},
         "--png " + (dir / "zero.png").string()});
  for (const auto& [args, named] : cases) {
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 2) << named << ": " << r.err;
    EXPECT_NE(r.err.find("cutaway: " + named + ": "), std::string::npos) << r.err;
  }
  const test::RunResult r = test::run_cutaway(cases[0].first);
  EXPECT_NE(r.err.find("is not a regular file"), std::string::npos) << r.err;
  std::vector<std::string> expected = {"fifo.pov", "folder.glb", "full.png", "null.glb"};
  if (device) expected.push_back("zero.png");
  EXPECT_EQ(entries(dir), expected);
  // Links to the devices: the outputs take the links' places.
  const test::RunResult linked =
      test::run_cutaway({"model", kTomato, "-q", "-o", (dir / "null.glb").string(), "--png",
                         (dir / "full.png").string()});
  EXPECT_EQ(linked.exit_code, 0) << linked.err;
  EXPECT_EQ(fs::symlink_status(dir / "null.glb").type(), fs::file_type::regular);
  EXPECT_EQ(fs::symlink_status(dir / "full.png").type(), fs::file_type::regular);
  EXPECT_GT(fs::file_size(dir / "null.glb"), 0u);
  struct stat st;
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  ASSERT_EQ(::stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(OutputFaults, MissingDirectoriesAreCreatedAndRemovedAgainWhenTheRunFails) {
  const fs::path dir = test::fresh_dir("output_faults_missing_dir");
  const test::RunResult ok =
      test::run_cutaway({"model", kTomato, "-q", "-o", (dir / "new/sub/x.glb").string()});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(test::files_in(dir), (std::vector<std::string>{"new/sub/x.glb"}));
  // A cut that misses the object fails after the outputs were registered.
  const test::RunResult bad = test::run_cutaway(
      {"piece", kTomato, "--cut", "plane:y=500", "-o", (dir / "other/sub/x.glb").string()});
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"new"}));
  EXPECT_EQ(entries(dir / "new/sub"), (std::vector<std::string>{"x.glb"}));
}

// A link at an output's path is replaced by the output, never written through: the file it
// points to keeps its bytes, and a dangling link's target is not created. A link and its
// target are two outputs now (two names), so both may be given at once.
TEST(OutputFaults, SymbolicLinksAreReplacedNeverWrittenThrough) {
  const fs::path dir = test::fresh_dir("output_faults_symlink");
  const test::RunResult direct =
      test::run_cutaway({"model", kTomato, "-q", "-o", (dir / "direct.glb").string()});
  ASSERT_EQ(direct.exit_code, 0) << direct.err;
  fs::create_directory(dir / "real");
  write_text(dir / "real/target.glb", "old glb");
  fs::create_symlink("real/target.glb", dir / "link.glb");   // to an existing file
  fs::create_symlink("real/new.glb", dir / "dangling.glb");  // to a file to be created
  for (const char* link : {"link.glb", "dangling.glb"}) {
    const test::RunResult r =
        test::run_cutaway({"model", kTomato, "-q", "-o", (dir / link).string()});
    EXPECT_EQ(r.exit_code, 0) << link << ": " << r.err;
    EXPECT_EQ(fs::symlink_status(dir / link).type(), fs::file_type::regular) << link;
    EXPECT_TRUE(test::read_file(dir / link) == test::read_file(dir / "direct.glb")) << link;
  }
  EXPECT_EQ(test::read_file(dir / "real/target.glb"), "old glb");
  EXPECT_EQ(entries(dir / "real"), (std::vector<std::string>{"target.glb"}));
}

TEST(OutputFaults, EmptyPathsAreRefused) {
  const fs::path dir = test::fresh_dir("output_faults_empty");
  const bool had_default = fs::exists(test::source_path("tomato.glb"));
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"model", kTomato, "-o", ""}, "cutaway: -o: the path is empty"},
      {{"model", kTomato, "--png", ""}, "cutaway: --png: the path is empty"},
      {{"section", kTomato, "--plane", "y=20", "-o", ""}, "cutaway: -o: the path is empty"},
      {{"piece", kTomato, "--cut", "halves", "-o", ""}, "cutaway: -o: the path is empty"},
      {{"scene", kScene, "-o", (dir / "a.glb").string(), "--render", ""},
       "cutaway: --render: the path is empty"},
      {{"variants", kTomato, "-o", ""}, "cutaway: -o: the path is empty"},
      {{"sheet", kTomato, "-o", ""}, "cutaway: -o: the path is empty"},
  };
  for (const auto& [args, message] : cases) {
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args[0] << ": " << r.err;
  }
  EXPECT_TRUE(entries(dir).empty());
  if (!had_default) {
    EXPECT_FALSE(fs::exists(test::source_path("tomato.glb")));
  }
}

TEST(OutputFaults, DirectoriesAndPathsGivenTwiceAreRefused) {
  const fs::path dir = test::fresh_dir("output_faults_dirs");
  fs::create_directory(dir / "d.glb");
  const std::string d = (dir / "d.glb").string(), a = (dir / "a.pov").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"model", kTomato, "-o", d}, "cutaway: -o " + d + ": is a directory"},
      {{"scene", kScene, "-o", a, "-o", a}, "cutaway: -o " + a + ": is given twice"},
  };
  for (const auto& [args, message] : cases) {
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"d.glb"}));
}

TEST(OutputFaults, TwoWritersOfOneFileLeaveOneWholeFile) {
  const fs::path dir = test::fresh_dir("output_faults_concurrent");
  std::string single[2];
  for (int i = 0; i < 2; ++i) {
    const fs::path out = dir / ("single" + std::to_string(i) + ".glb");
    const test::RunResult r = test::run_cutaway(
        {"model", kTomato, "-q", "--seed", std::to_string(i + 1), "-o", out.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    single[i] = test::read_file(out);
    fs::remove(out);
  }
  ASSERT_NE(single[0], single[1]);
  const fs::path same = dir / "same.glb";
  for (int round = 0; round < 3; ++round) {
    Child c[2];
    for (int i = 0; i < 2; ++i) {
      Spawn s;
      s.args = {"model", kTomato, "-q", "--seed", std::to_string(i + 1), "-o", same.string()};
      c[i] = start(s, dir.parent_path() / (dir.filename().string() + std::to_string(i) + ".log"));
    }
    for (const Child& child : c) {
      const int status = wait_for(child);
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << test::read_file(child.log);
      fs::remove(child.log);
    }
    const std::string result = test::read_file(same);
    EXPECT_TRUE(result == single[0] || result == single[1])
        << "round " << round << ": " << result.size() << " bytes, neither run's file";
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"same.glb"}));
  }
}

// The library itself: companions, describe(), abort().

TEST(OutputSetLibrary, CommitsCompanionFilesAndAbortLeavesNothing) {
  const fs::path dir = test::fresh_dir("output_set");
  write_text(dir / "a.txt", "old a");
  {
    OutputSet set;
    const fs::path a = set.add("-o", (dir / "a.txt").string());
    EXPECT_NE(a.parent_path(), dir);
    write_file_atomically(a, "new a");
    write_file_atomically(a.parent_path() / "a.extra", "companion");
    EXPECT_EQ(test::read_file(dir / "a.txt"), "old a");  // nothing before commit()
    set.commit();
  }
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"a.extra", "a.txt"}));
  EXPECT_EQ(test::read_file(dir / "a.txt"), "new a");
  {
    OutputSet set;
    const fs::path a = set.add("-o", (dir / "a.txt").string());
    const fs::path b = set.add("--png", (dir / "new/b.png").string());
    write_file_atomically(a, "newer a");
    EXPECT_EQ(set.describe("cannot write " + b.string() + ": reason"),
              "cannot write " + (dir / "new/b.png").string() + ": reason");
  }  // no commit(): aborted
  EXPECT_EQ(entries(dir), (std::vector<std::string>{"a.extra", "a.txt"}));
  EXPECT_EQ(test::read_file(dir / "a.txt"), "new a");
}

}  // namespace
}  // namespace cutaway
