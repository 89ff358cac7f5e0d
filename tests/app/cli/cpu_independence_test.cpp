// Same seed, same bytes, on any CPU (doc/architecture.md, Determinism): each case is made three
// ways on this machine and must give byte-identical files: as it runs by default; with glibc
// told to use its baseline math routines instead of its FMA/AVX2 ones (GLIBC_TUNABLES); and
// with Embree forced to its SSE4.2 kernels (CUTAWAY_EMBREE_ISA) instead of the best this CPU has.
// Before the portable libm and the decided PMVC hits, the tunables changed a tomato wedges
// cut's triangle count and SSE4.2 changed the salad's colours. `make test-cpus` adds a fourth
// way, an emulated SSE4.2-only CPU (tests/app/cli/emulated_cpu_test.sh).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// One way of running the CLI: an environment variable set for the run (none for the default).
struct Way {
  const char* name;
  const char* variable;
  const char* value;
};

constexpr Way kWays[] = {
    {"default", nullptr, nullptr},
    {"baseline-libm", "GLIBC_TUNABLES", "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX,-FMA4,-AVX512F"},
    {"embree-sse4.2", "CUTAWAY_EMBREE_ISA", "sse4.2"},
};

/// Every regular file under `dir`, by its path relative to it, with its bytes; but a batch's
/// timings.jsonl, which records how long each asset took.
std::map<std::string, std::string> files_under(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "timings.jsonl")
      out[fs::relative(e.path(), dir).string()] = test::read_file(e.path());
  return out;
}

/// Runs `args` (with OUT replaced by a fresh folder of each way) the three ways and expects
/// every file written to be the same in all of them, and at least `at_least` files. Each run
/// has an empty cut cache of its own (run_cutaway); a scene or a batch is also given --stats
/// and must report every cut object and placement made, none read back (test::made_afresh),
/// so that each way runs PMVC, the meshing and the physics itself.
void expect_same_bytes_every_way(const std::string& name, const std::vector<std::string>& args,
                                 size_t at_least) {
  std::map<std::string, std::string> first;
  for (const Way& way : kWays) {
    const fs::path out = test::fresh_dir(name + "-" + way.name);
    std::vector<std::string> a;
    for (const std::string& arg : args) {
      std::string s = arg;
      if (const auto at = s.find("OUT"); at != std::string::npos) s.replace(at, 3, out.string());
      a.push_back(s);
    }
    const bool cached_command = args.front() == "scene" || args.front() == "batch";
    if (cached_command) a.push_back("--stats");
    if (way.variable) ::setenv(way.variable, way.value, 1);
    const test::RunResult r = test::run_cutaway(a);
    if (way.variable) ::unsetenv(way.variable);
    ASSERT_EQ(r.exit_code, 0) << way.name << ": " << r.err;
    if (cached_command) {
      EXPECT_TRUE(test::made_afresh(r)) << way.name;
    }
    const auto files = files_under(out);
    ASSERT_GE(files.size(), at_least) << way.name;
    if (first.empty()) {
      first = files;
      continue;
    }
    ASSERT_EQ(files.size(), first.size()) << way.name;
    for (const auto& [file, bytes] : first) {
      const auto it = files.find(file);
      ASSERT_NE(it, files.end()) << way.name << " did not write " << file;
      EXPECT_TRUE(it->second == bytes) << file << " differs between default and " << way.name;
    }
  }
}

TEST(CpuIndependence, PieceWithDice) {
  expect_same_bytes_every_way(
      "dice",
      {"piece", "templates/kiwi.yaml", "--cut", "dice:20", "--seed", "5", "-o", "OUT/kiwi.glb"}, 1);
}

TEST(CpuIndependence, PieceWithDiceAsPovRay) {
  expect_same_bytes_every_way(
      "dice-pov",
      {"piece", "templates/kiwi.yaml", "--cut", "dice:20", "--seed", "5", "-o", "OUT/kiwi.pov"}, 1);
}

TEST(CpuIndependence, SectionOfASeededVariant) {
  expect_same_bytes_every_way("section",
                              {"section", "templates/tomato.yaml", "--plane", "2,20,1/0.3,1,0.2",
                               "--seed", "9", "-o", "OUT/cut.glb"},
                              1);
}

TEST(CpuIndependence, SceneWithPhysicsAndTextures) {
  expect_same_bytes_every_way(
      "scene", {"scene", "tests/data/scenes/tiny.yaml", "-o", "OUT/tiny.glb", "-o", "OUT/tiny.pov"},
      2);
}

TEST(CpuIndependence, BatchAssetsAndManifest) {
  const fs::path dir = test::fresh_dir("batch-file");
  const fs::path file = dir / "one.yaml";
  {
    std::ofstream f(file);
    f << "format: cutaway-batch/1\nname: one\nseed: 3\nitems:\n"
         "  - template: persimmon\n    count: 1\n    cuts:\n      - {type: wedges, count: 3}\n";
  }
  // The asset, its thumbnail, the manifest and batch.json.
  expect_same_bytes_every_way("batch", {"batch", file.string(), "-o", "OUT/assets"}, 4);
}

TEST(CpuIndependence, VariantSet) {
  expect_same_bytes_every_way(
      "variants",
      {"variants", "templates/tomato.yaml", "--count", "3", "--seed", "4", "-o", "OUT/set/"}, 3);
}

}  // namespace
}  // namespace cutaway
