// read_regular_file: a FIFO, a device or a directory is refused without reading from it (a FIFO
// would block for ever, /dev/zero never ends), a file over the limit before it is read.
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

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
  // A block would hang the test (CTest's timeout ends it); a read of /dev/zero would count
  // here. Measured: about 100 bytes, the count's own read of /proc/thread-self/io.
  ASSERT_EQ(::mkfifo((dir / "f.yaml").c_str(), 0600), 0);
  const uint64_t read_before = test::thread_bytes_read();
  EXPECT_EQ(refusal(dir / "f.yaml", 100), "is not a regular file (a FIFO, socket or device)");
  EXPECT_EQ(refusal("/dev/zero", 100), "is not a regular file (a FIFO, socket or device)");
  EXPECT_EQ(refusal("/dev/null", 100), "is not a regular file (a FIFO, socket or device)");
  EXPECT_LT(test::thread_bytes_read() - read_before, 1024u) << "bytes read";
}

TEST(FileRead, RefusesALargeFileBeforeReadingIt) {
  // A sparse 1 GiB file: reading it would take seconds and a gigabyte; the size decides.
  const fs::path dir = test::fresh_dir("file_read");
  { std::ofstream(dir / "big.yaml"); }
  fs::resize_file(dir / "big.yaml", uint64_t{1} << 30);
  // Nothing of the file is read: measured, about 100 bytes (the count's own read of
  // /proc/thread-self/io); the bound is far below the 16 MiB limit and one page of the file.
  const uint64_t read_before = test::thread_bytes_read();
  EXPECT_EQ(refusal(dir / "big.yaml", uint64_t{16} << 20), "is larger than 16 MiB");
  EXPECT_LT(test::thread_bytes_read() - read_before, 1024u) << "bytes read";
  // Nor is a buffer of the file's size, or of the limit, allocated.
  const auto refused = [&] {
    return refusal(dir / "big.yaml", uint64_t{16} << 20) == "is larger than 16 MiB" ? 0 : 1;
  };
  EXPECT_EQ(test::exit_code_within_address_space(uint64_t{8} << 20, refused), 0)
      << "100: it allocated more than 8 MiB";
}

// A file costs its size once: one allocation of st_size, read to its end, no growth copy. A
// child process reads a 512 MiB (sparse) file with an address space of what it has mapped
// plus 1.1 times the file: a second buffer (a growth copy) would not fit.
TEST(FileRead, AFileCostsItsSizeOnce) {
  const fs::path file = test::fresh_dir("file_read_once") / "big.bin";
  const uint64_t size = uint64_t{512} << 20;
  std::ofstream(file).close();
  fs::resize_file(file, size);
  const auto read_whole = [&] { return read_regular_file(file, size).size() == size ? 0 : 2; };
  EXPECT_EQ(test::exit_code_within_address_space(size + size / 10, read_whole), 0)
      << "100: it did not fit in 1.1 times the file";
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
