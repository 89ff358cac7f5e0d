// read_regular_file: a FIFO, a device or a directory is refused without reading from it (a FIFO
// would block for ever, /dev/zero never ends), a file over the limit before it is read.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>

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

TEST(FileRead, StatesSizesInTheLargestWholeUnit) {
  EXPECT_EQ(byte_size_words(uint64_t{16} << 20), "16 MiB");
  EXPECT_EQ(byte_size_words(uint64_t{4} << 30), "4 GiB");
  EXPECT_EQ(byte_size_words(3072), "3 KiB");
  EXPECT_EQ(byte_size_words(1000), "1000 bytes");
  EXPECT_EQ(byte_size_words(0), "0 bytes");
}

}  // namespace
}  // namespace cutaway
