// The places cutaway writes into, attacked as a hostile or careless user would: a link planted
// in a batch's output folder or at a cache entry's name is replaced, never written through; a
// --cache folder keeps every file that is not the cache's; something at an entry's name that no
// entry can be (a FIFO, a huge file) costs that entry only; a cache folder other users can write
// is refused unless shared on purpose.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include "test_support.h"

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

const std::string kCherryScene = source_path("tests/data/scenes/cherry-board.yaml").string();
const std::string kCherryBatch = source_path("tests/data/batches/cherry-volumes.yaml").string();

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

/// Every entry file of the cut cache in `dir` (its own layout folder), largest first.
std::vector<fs::path> cache_entries(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir / "cutaway-cache-v2"))
    if (e.symlink_status().type() == fs::file_type::regular && e.path().extension() == ".cut")
      out.push_back(e.path());
  std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
    return fs::file_size(a) > fs::file_size(b);
  });
  return out;
}

/// The cherry scene through the cache `cache`, written to `out`; its bytes.
RunResult cherry_scene(const fs::path& cache, const fs::path& out,
                       std::vector<std::string> more = {}) {
  std::vector<std::string> args = {"scene",        kCherryScene, "--cache",
                                   cache.string(), "-o",         out.string()};
  args.insert(args.end(), more.begin(), more.end());
  return run_cutaway(args);
}

TEST(FileSafety, ABatchReRunReplacesALinkPlantedInItsFolderAndLeavesItsTargetAlone) {
  const fs::path dir = fresh_dir("batch_link");
  const fs::path out = dir / "out", victim = dir / "victim" / "important.txt";
  write_text(victim, "precious user data");
  RunResult r = run_cutaway({"-q", "batch", kCherryBatch, "-o", out.string(), "--no-cache"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path json = out / "cherry-11.volume.json";
  ASSERT_TRUE(fs::is_regular_file(json));
  const std::string built = read_file(json);
  fs::remove(json);
  fs::create_symlink(victim, json);
  // merge calls the asset damaged (a link is never read as the asset's file) ...
  r = run_cutaway({"batch", "merge", out.string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("missing or changed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cherry-11"), std::string::npos) << r.err;
  // ... and a re-run builds it again, replacing the link by the file.
  r = run_cutaway({"batch", kCherryBatch, "-o", out.string(), "--no-cache"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 assets built"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(victim), "precious user data");
  EXPECT_EQ(fs::symlink_status(json).type(), fs::file_type::regular);
  EXPECT_EQ(read_file(json), built);
  r = run_cutaway({"batch", "merge", out.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// A batch folder's file replaced by a 3.9 GB (sparse) file: merge hashes it a mebibyte at a
// time, so it stays within a 1 GiB address space and reports the asset damaged.
TEST(FileSafety, BatchMergeHashesAHugeFileWithinBoundedMemory) {
  const fs::path out = fresh_dir("batch_huge") / "out";
  RunResult r = run_cutaway({"-q", "batch", kCherryBatch, "-o", out.string(), "--no-cache"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path vdb = out / "cherry-11.volume.vdb";
  ASSERT_TRUE(fs::exists(vdb));
  fs::remove(vdb);
  std::ofstream(vdb).close();
  fs::resize_file(vdb, uint64_t{3900} << 20);
  const LimitedRun merged =
      run_cutaway_limited({"batch", "merge", out.string()}, uint64_t{1} << 30, 120);
  EXPECT_EQ(merged.exit_code, 3) << merged.err;
  EXPECT_NE(merged.err.find("cherry-11"), std::string::npos) << merged.err;
  EXPECT_LT(merged.peak_rss_bytes, uint64_t{256} << 20);
  fs::remove(vdb);
}

TEST(FileSafety, ADanglingLinkAtAnEntryIsReplacedAndNothingIsCreatedOutsideTheCache) {
  const fs::path dir = fresh_dir("cache_dangling"), cache = dir / "cache";
  const fs::path outside = dir / "victim" / "created-by-cache.txt";
  fs::create_directories(outside.parent_path());
  RunResult r = cherry_scene(cache, dir / "first.glb", {"-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<fs::path> files = cache_entries(cache);
  ASSERT_EQ(files.size(), 2u);
  fs::remove(files[0]);
  fs::create_symlink(outside, files[0]);
  r = cherry_scene(cache, dir / "again.glb", {"-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(outside));
  EXPECT_EQ(fs::symlink_status(files[0]).type(), fs::file_type::regular);
  EXPECT_EQ(read_file(dir / "again.glb"), read_file(dir / "first.glb"));
}

// The cache lives in its own folder (cutaway-cache-v2 with CACHEDIR.TAG) and lists, cleans and
// evicts only there: files of the user's named like its temporaries and entries stay, however
// old, through a first store and through eviction.
TEST(FileSafety, ACacheFolderKeepsEveryFileThatIsNotTheCaches) {
  const fs::path dir = fresh_dir("cache_user_files"), cache = dir / "user";
  const std::vector<fs::path> mine = {cache / "projects/film/scene12.cut",
                                      cache / "docs/report.tmp-final.odt",
                                      cache / "ab/0123456789abcdef.cut",
                                      cache / "0123456789abcdef.cut.tmp-abcdef"};
  for (const fs::path& f : mine) {
    write_text(f, "user data " + f.filename().string());
    const auto old = fs::file_time_type::clock::now() - std::chrono::hours(48);
    fs::last_write_time(f, old);
  }
  RunResult r = cherry_scene(cache, dir / "a.glb", {"-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(cache / "cutaway-cache-v2" / "CACHEDIR.TAG"));
  // Another seed with a bound below one entry: the cache evicts its own entries only.
  r = cherry_scene(cache, dir / "b.glb", {"--seed", "2", "--cache-size", "1M", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("\"evicted\":0"), std::string::npos) << r.err;
  for (const fs::path& f : mine) {
    ASSERT_TRUE(fs::is_regular_file(f)) << f;
    EXPECT_EQ(read_file(f), "user data " + f.filename().string());
  }
}

// A FIFO at one entry's name: that entry is removed and stored again (the FIFO is never opened
// for writing, so nothing blocks), and every other entry is stored as usual.
TEST(FileSafety, AFifoAtAnEntryCostsThatEntryOnly) {
  const fs::path dir = fresh_dir("cache_fifo"), cache = dir / "cache";
  RunResult r = cherry_scene(cache, dir / "first.glb", {"-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<fs::path> files = cache_entries(cache);
  ASSERT_EQ(files.size(), 2u);
  for (const fs::path& f : files) fs::remove(f);
  ASSERT_EQ(::mkfifo(files[0].c_str(), 0644), 0);
  r = cherry_scene(cache, dir / "again.glb", {"--stats"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("\"stored\":2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(files[0].string()), std::string::npos) << r.err;
  EXPECT_EQ(cache_entries(cache).size(), 2u);
  EXPECT_EQ(read_file(dir / "again.glb"), read_file(dir / "first.glb"));
}

// A 3.9 GB (sparse) file at an entry's name is never read (its size is over an entry's bound):
// it is removed with a warning naming it, and the run stays within a 3 GB address space.
TEST(FileSafety, AHugeFileAtAnEntryIsRemovedUnread) {
  const fs::path dir = fresh_dir("cache_huge"), cache = dir / "cache";
  RunResult r = cherry_scene(cache, dir / "first.glb", {"-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path entry = cache_entries(cache)[0];
  fs::resize_file(entry, uint64_t{3900} << 20);
  const LimitedRun limited = run_cutaway_limited({"scene", kCherryScene, "--cache", cache.string(),
                                                  "-o", (dir / "again.glb").string()},
                                                 uint64_t{3} << 30, 120);
  EXPECT_EQ(limited.exit_code, 0) << limited.err;
  EXPECT_NE(limited.err.find(entry.string()), std::string::npos) << limited.err;
  EXPECT_NE(limited.err.find("is larger than 1 GiB"), std::string::npos) << limited.err;
  EXPECT_LT(fs::file_size(entry), uint64_t{100} << 20);  // stored again, at its own size
  EXPECT_EQ(read_file(dir / "again.glb"), read_file(dir / "first.glb"));
}

TEST(FileSafety, ACacheFolderOtherUsersCanWriteIsRefusedUnlessShared) {
  const fs::path dir = fresh_dir("cache_shared"), cache = dir / "cache";
  RunResult r = cherry_scene(cache, dir / "first.glb", {"-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  fs::permissions(cache / "cutaway-cache-v2", fs::perms::all);  // 0777
  r = cherry_scene(cache, dir / "refused.glb");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--cache " + cache.string() + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("writable by other users (mode 0777)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "refused.glb"));
  r = cherry_scene(cache, dir / "shared.glb", {"--cache-shared", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("\"hits\":2"), std::string::npos) << r.err;
  // A layout folder the cache did not make (no marker) is not used.
  const fs::path other = dir / "other";
  fs::create_directories(other / "cutaway-cache-v2");
  fs::permissions(other / "cutaway-cache-v2", fs::perms::owner_all, fs::perm_options::replace);
  r = cherry_scene(other, dir / "other.glb");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("has no CACHEDIR.TAG"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cutaway::test
