// measured_run REPORT PROGRAM [ARGS...]: runs PROGRAM with ARGS (no shell; stdin, stdout,
// stderr, environment, working directory and resource limits inherited), waits for it, and
// writes one line to the file REPORT:
//
//   exit CODE signal SIGNAL peak_rss_kib KIB read_bytes BYTES written_bytes BYTES
//
// CODE is -1 when a signal ended it. peak_rss_kib is the program's own peak resident memory
// (wait4's ru_maxrss for that child). A process forked from a large one, such as a test
// process, carries that process's peak into the child it execs (the kernel keeps the larger of
// the two); this small program starts the measured one itself, so that the peak is the
// program's. read_bytes and written_bytes are what its read and write calls moved (rchar and
// wchar of /proc/PID/io, taken once it has ended but before it is reaped; -1 when the kernel
// keeps no I/O counts).
//
// Exit status: 0 with the report written; 2 for a wrong command line; 3 when the report cannot
// be written; 127 when PROGRAM cannot be started (no report).
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

namespace {

/// The counter `key` ("rchar", "wchar") in /proc/`pid`/io; -1 when it cannot be read.
long long io_count(pid_t pid, const char* key) {
  const std::string path = "/proc/" + std::to_string(pid) + "/io";
  FILE* io = std::fopen(path.c_str(), "r");
  if (io == nullptr) return -1;
  char name[64];
  long long value = -1, found = -1;
  while (std::fscanf(io, "%63[^:]: %lld\n", name, &value) == 2)
    if (std::strcmp(name, key) == 0) found = value;
  std::fclose(io);
  return found;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: measured_run REPORT PROGRAM [ARGS...]\n");
    return 2;
  }
  int started[2];  // closed on exec; an errno written to it says the exec failed
  if (::pipe2(started, O_CLOEXEC) != 0) return 127;
  const pid_t pid = ::fork();
  if (pid < 0) return 127;
  if (pid == 0) {
    ::close(started[0]);
    ::execv(argv[2], argv + 2);
    const int error = errno;
    [[maybe_unused]] const ssize_t told = ::write(started[1], &error, sizeof error);
    ::_exit(127);
  }
  ::close(started[1]);
  int error = 0;
  ssize_t n;
  while ((n = ::read(started[0], &error, sizeof error)) < 0 && errno == EINTR) {
  }
  ::close(started[0]);
  // Wait for its end without reaping it: /proc/PID/io is there until wait4 below.
  siginfo_t ended{};
  while (::waitid(P_PID, static_cast<id_t>(pid), &ended, WEXITED | WNOWAIT) != 0) {
    if (errno != EINTR) return 127;
  }
  const long long read_bytes = io_count(pid, "rchar");
  const long long written_bytes = io_count(pid, "wchar");
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, 0, &usage) != pid) {
    if (errno != EINTR) return 127;
  }
  if (n > 0) {
    std::fprintf(stderr, "measured_run: cannot run %s: %s\n", argv[2], std::strerror(error));
    return 127;
  }
  FILE* report = std::fopen(argv[1], "w");
  if (report == nullptr) return 3;
  std::fprintf(report, "exit %d signal %d peak_rss_kib %ld read_bytes %lld written_bytes %lld\n",
               WIFEXITED(status) ? WEXITSTATUS(status) : -1,
               WIFSIGNALED(status) ? WTERMSIG(status) : 0, usage.ru_maxrss, read_bytes,
               written_bytes);
  return std::fclose(report) == 0 ? 0 : 3;
}
