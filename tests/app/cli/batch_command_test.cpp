// `cutaway batch` and `cutaway batch merge` at the command line: bad input is exit code 2 with
// the file, line, column and field, and writes nothing; an incomplete batch does not merge.
// (The whole path, local and on Slurm, is the test SlurmBatchArrayMatchesLocalRun.)
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "test_support.h"

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

TEST(BatchCommand, BadBatchFileIsExitCode2AndWritesNothing) {
  const fs::path dir = fresh_dir("batch-cli");
  const fs::path file = dir / "bad.yaml";
  std::ofstream(file) << "format: cutaway-batch/1\nname: bad\nitems:\n  - template: tomato\n"
                         "    count: many\n";
  const RunResult r = run_cutaway({"batch", file.string(), "-o", (dir / "out").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("bad.yaml:5:12: items[0].count: "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(BatchCommand, MergeRefusesAFolderThatIsNoBatchAndAnIncompleteBatch) {
  const fs::path dir = fresh_dir("batch-merge");
  RunResult r = run_cutaway({"batch", "merge", dir.string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("batch.json is missing"), std::string::npos) << r.err;
  // A one-shard-of-four run of a batch: the other shards are reported missing.
  r = run_cutaway({"-q", "batch", source_path("tests/data/batches/four-variants.yaml").string(),
                   "-o", dir.string(), "--shard", "4/4", "--backend", "cpu"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cutaway({"batch", "merge", dir.string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;  // its own code: more shards are due
  EXPECT_NE(r.err.find("5 assets missing (in no manifest): persimmon-7-wedges-4"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "manifest.jsonl"));
}

// A sampled thumbnail whose recorded hash matches but which is not a PNG (damaged where the
// hash was taken): merge refuses the batch with exit code 2 and writes nothing, not even the
// manifest it used to rewrite before it read the thumbnails.
TEST(BatchCommand, MergeReadsEveryThumbnailBeforeWritingAnything) {
  const fs::path dir = fresh_dir("batch-merge-thumbnail");
  RunResult r =
      run_cutaway({"-q", "batch", source_path("tests/data/batches/four-variants.yaml").string(),
                   "-o", dir.string(), "--shard", "1/1", "--backend", "cpu"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path manifest = dir / "manifest-1-of-1.jsonl";
  std::string lines = read_file(manifest);
  ASSERT_FALSE(lines.empty());
  // Damage every thumbnail the manifest names, with a hash that matches the new bytes.
  const std::string damaged = "not a PNG image";
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>([&] {
                  uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64
                  for (const unsigned char c : damaged) h = (h ^ c) * 0x100000001b3ULL;
                  return h;
                }()));
  int thumbnails = 0;
  for (size_t at = lines.find("\"thumbnail\":\""); at != std::string::npos;
       at = lines.find("\"thumbnail\":\"", at + 1)) {
    const size_t start = at + 13, end = lines.find('"', start);
    std::ofstream(dir / lines.substr(start, end - start), std::ios::binary) << damaged;
    const size_t h = lines.find("\"thumbnail_fnv1a64\":\"", end) + 21;
    lines.replace(h, 16, hash);
    ++thumbnails;
  }
  ASSERT_GT(thumbnails, 0) << lines;
  std::ofstream(manifest, std::ios::binary) << lines;
  r = run_cutaway({"batch", "merge", dir.string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("cannot be used"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "manifest.jsonl"));
  EXPECT_FALSE(fs::exists(dir / "contact-sheet.png"));
}

TEST(BatchCommand, SlurmDryRunWritesTheScriptOnly) {
  const fs::path dir = fresh_dir("batch-slurm");
  const RunResult r =
      run_cutaway({"-q", "batch", source_path("tests/data/batches/four-variants.yaml").string(),
                   "-o", dir.string(), "--slurm", "--array", "3", "--dry-run"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = read_file(dir / "batch.sbatch");
  EXPECT_NE(script.find("#SBATCH --array=1-3"), std::string::npos) << script;
  EXPECT_NE(script.find("--shard \"${SLURM_ARRAY_TASK_ID}/3\""), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "batch.json"));
}

}  // namespace
}  // namespace cutaway::test

namespace cutaway::test {
namespace {

// A batch built again with the cut cache of a first build: its objects are read back, not cut,
// and every file is the same as without the cache (the models, the pieces, the thumbnails, the
// manifest; not the timings). The stats tell the runs apart: test::made_afresh, which every
// byte comparison across runs asserts, accepts the first two and catches the third.
TEST(BatchCommand, ReadsCutObjectsFromTheCacheAndWritesTheSameFiles) {
  const fs::path dir = fresh_dir("batch-cache");
  const std::string batch = source_path("tests/data/batches/four-variants.yaml").string();
  const std::vector<std::string> shard = {"--shard", "1/4", "--backend", "cpu"};
  auto run = [&](const std::string& out, std::vector<std::string> cache) {
    std::vector<std::string> args = {"batch", batch, "-o", (dir / out).string(), "--stats"};
    args.insert(args.end(), shard.begin(), shard.end());
    args.insert(args.end(), cache.begin(), cache.end());
    return run_cutaway(args);
  };
  const RunResult none = run("none", {"--no-cache"});
  ASSERT_EQ(none.exit_code, 0) << none.err;
  EXPECT_TRUE(made_afresh(none));
  const RunResult first = run("first", {"--cache", (dir / "cache").string()});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(first.err.find("read from the cut cache"), std::string::npos) << first.err;
  EXPECT_TRUE(made_afresh(first));
  const RunResult again = run("again", {"--cache", (dir / "cache").string()});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("2 of the assets built were read from the cut cache"), std::string::npos)
      << again.err;
  EXPECT_FALSE(made_afresh(again));
  const std::vector<std::string> files = files_in(dir / "none");
  ASSERT_GE(files.size(), 4u);
  for (const char* out : {"first", "again"}) {
    EXPECT_EQ(files_in(dir / out), files) << out;
    for (const std::string& f : files)
      if (f.rfind("timings-", 0) != 0) {  // wall seconds
        EXPECT_EQ(read_file(dir / out / f), read_file(dir / "none" / f)) << out << "/" << f;
      }
  }
}

}  // namespace
}  // namespace cutaway::test
