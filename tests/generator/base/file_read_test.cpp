// read_regular_file: a FIFO, a device or a directory is refused without reading from it (a FIFO
// would block for ever, /dev/zero never ends), a file over the limit before it is read.
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/file_read.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// The rule read_regular_file refuses `path` with ("" when it reads it).
std::string refusal(const fs::path& path, uint64_t max_bytes) {
  try {
    read_regular_file(path, max_bytes);
  } catch (const FileReadError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot read " + path.string() + ": " + e.rule());
    return e.rule();
  }
  return "";
}

TEST(FileRead, ReadsARegularFileWholeUpToTheLimit) {
  const fs::path dir = test::fresh_dir("file_read");
  std::ofstream(dir / "a.txt") << "0123456789";
  EXPECT_EQ(read_regular_file(dir / "a.txt", 10), "0123456789");
  EXPECT_EQ(read_regular_file(dir / "a.txt", 1000), "0123456789");
  EXPECT_EQ(refusal(dir / "a.txt", 9), "is larger than 9 bytes");
  std::ofstream(dir / "empty.txt");
  EXPECT_EQ(read_regular_file(dir / "empty.txt", 0), "");
  // Through a symbolic link, as any program reads.
  fs::create_symlink(dir / "a.txt", dir / "link.txt");
  EXPECT_EQ(read_regular_file(dir / "link.txt", 10), "0123456789");
}

TEST(FileRead, RefusesWhatIsNotARegularFileWithoutBlocking) {
  const fs::path dir = test::fresh_dir("file_read");
  EXPECT_EQ(refusal(dir / "missing.yaml", 100), "does not exist");
  EXPECT_EQ(refusal(dir, 100), "is a directory");
  // Nobody writes into the FIFO: opening it for reading would block for ever.
  ASSERT_EQ(::mkfifo((dir / "f.yaml").c_str(), 0600), 0);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(refusal(dir / "f.yaml", 100), "is not a regular file (a FIFO, socket or device)");
  EXPECT_EQ(refusal("/dev/zero", 100), "is not a regular file (a FIFO, socket or device)");
  EXPECT_EQ(refusal("/dev/null", 100), "is not a regular file (a FIFO, socket or device)");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
}

TEST(FileRead, RefusesALargeFileBeforeReadingIt) {
  // A sparse 1 GiB file: reading it would take seconds and a gigabyte; the size decides.
  const fs::path dir = test::fresh_dir("file_read");
  { std::ofstream(dir / "big.yaml"); }
  fs::resize_file(dir / "big.yaml", uint64_t{1} << 30);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(refusal(dir / "big.yaml", uint64_t{16} << 20), "is larger than 16 MiB");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.5);
}

/// The address space the process has mapped now, bytes (VmSize of /proc/self/status).
uint64_t mapped_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) return std::stoull(line.substr(7)) * 1024;
  return 0;
}

// A file costs its size once: one allocation of st_size, read to its end, no growth copy. A
// child process reads a 512 MiB (sparse) file with an address space of what it has mapped
// plus 1.1 times the file: a second buffer (a growth copy) would not fit.
TEST(FileRead, AFileCostsItsSizeOnce) {
  const fs::path file = test::fresh_dir("file_read_once") / "big.bin";
  const uint64_t size = uint64_t{512} << 20;
  std::ofstream(file).close();
  fs::resize_file(file, size);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const rlimit limit{mapped_bytes() + size + size / 10, mapped_bytes() + size + size / 10};
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(3);
    try {
      const std::string bytes = read_regular_file(file, size);
      ::_exit(bytes.size() == size ? 0 : 2);
    } catch (...) {
      ::_exit(1);
    }
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: it did not fit in 1.1 times the file";
  fs::remove(file);
}

TEST(FileRead, StatesSizesInTheLargestWholeUnit) {
  EXPECT_EQ(byte_size_words(uint64_t{16} << 20), "16 MiB");
  EXPECT_EQ(byte_size_words(uint64_t{4} << 30), "4 GiB");
  EXPECT_EQ(byte_size_words(3072), "3 KiB");
  EXPECT_EQ(byte_size_words(1000), "1000 bytes");
  EXPECT_EQ(byte_size_words(0), "0 bytes");
}

}  // namespace
}  // namespace cutaway
