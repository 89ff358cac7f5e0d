// Portability benchmark: what "the same bytes on any CPU" (doc/architecture.md, Determinism)
// costs. The tomato cut (wedges:4) and the default salad scene, each made as `cutaway` makes
// them now and as cutaway 0.1 made them, in one run, alternating, best of N:
//   - libm: `cutaway` (SLEEF's portable functions) or `cutaway_glibc_libm` (the same command
//     line linked against the C library's per-CPU libm);
//   - hits: PMVC hits decided in double precision (the default) or Embree's own float hits
//     (CUTAWAY_PMVC_HITS=embree).
// before = glibc libm + Embree's hits (0.1), after = portable libm + decided hits (now); the two
// mixed rows say which part costs what. -ffp-contract=off has no cost to measure on x86-64: the
// build targets baseline x86-64, which has no FMA instruction to contract into.
//
// Run:   make bench
//   or:  cmake --build build --target bench_portability && ./build/bench_portability
// Options: --repeat N (best of N, default 3), --only tomato|salad.
// One line per case and configuration, then one line per case with after/before against the
// target of at most 15 % slower.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "base/child_process.h"
#include "base/timer.h"
#include "batch/variant_batch.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Config {
  const char* name;
  const char* exe;
  bool embree_hits;
};

// Before first, after last: the rows read from 0.1 to now.
const Config kConfigs[] = {{"before (glibc libm, embree hits)", CUTAWAY_GLIBC_LIBM_EXE, true},
                           {"glibc libm, decided hits", CUTAWAY_GLIBC_LIBM_EXE, false},
                           {"portable libm, embree hits", CUTAWAY_EXE, true},
                           {"after (portable libm, decided hits)", CUTAWAY_EXE, false}};
constexpr size_t kBefore = 0, kAfter = 3;

struct Case {
  const char* name;
  std::vector<std::string> args;  ///< after the program's name; OUT is the output .glb
};

/// Seconds the command took, and the FNV-1a hash of the .glb it wrote.
struct Run {
  double seconds = 1e300;
  uint64_t glb_hash = 0;
};

Run run_once(const Config& config, const Case& c, const fs::path& out) {
  std::vector<std::string> args = {
      "env", config.embree_hits ? "CUTAWAY_PMVC_HITS=embree" : "CUTAWAY_PMVC_HITS=decided",
      config.exe};
  for (const std::string& a : c.args) args.push_back(a == "OUT" ? out.string() : a);
  const auto t0 = Clock::now();
  const cutaway::ChildResult r = cutaway::run_child(
      CUTAWAY_SOURCE_DIR, cutaway::find_executable("env", "install coreutils"), args);
  const double s = cutaway::seconds_since(t0);
  if (!WIFEXITED(r.status) || WEXITSTATUS(r.status) != 0) {
    std::fprintf(stderr, "bench_portability: %s (%s) failed:\n%s\n", c.name, config.name,
                 r.output.c_str());
    std::exit(1);
  }
  return {s, cutaway::fnv1a64(cutaway::read_file_bytes(out))};
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 3;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
  }
  const std::vector<Case> cases = {
      {"tomato",
       {"piece", "templates/tomato.yaml", "--cut", "wedges:4", "--seed", "3", "--backend", "cpu",
        "-q", "-o", "OUT"}},
      {"salad",
       {"scene", "scenes/salad.yaml", "--seed", "3", "--backend", "cpu", "-q", "-o", "OUT"}}};
  const fs::path dir =
      fs::temp_directory_path() / ("cutaway_bench_portability_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::printf("# bench_portability: cpu backend, all %u cores, best of %d, configurations "
              "alternating; whole processes (parse to written .glb)\n",
              std::thread::hardware_concurrency(), repeat);
  std::fflush(stdout);
  for (const Case& c : cases) {
    if (!only.empty() && only != c.name) continue;
    Run best[std::size(kConfigs)];
    bool after_stable = true;
    for (int r = 0; r < repeat; ++r) {
      for (size_t k = 0; k < std::size(kConfigs); ++k) {
        const Run run = run_once(kConfigs[k], c, dir / (std::string(c.name) + ".glb"));
        if (r > 0 && run.glb_hash != best[k].glb_hash && k == kAfter) after_stable = false;
        best[k] = {std::min(best[k].seconds, run.seconds), run.glb_hash};
      }
    }
    for (size_t k = 0; k < std::size(kConfigs); ++k) {
      std::printf("%-7s %-36s seconds=%.3f vs_before=%+.1f%% glb_fnv1a64=%s\n", c.name,
                  kConfigs[k].name, best[k].seconds,
                  100 * (best[k].seconds / best[kBefore].seconds - 1),
                  cutaway::hex64(best[k].glb_hash).c_str());
    }
    const double ratio = best[kAfter].seconds / best[kBefore].seconds;
    std::printf("%-7s after/before=%.3f (target <= 1.15: %s); after's bytes the same in every "
                "run: %s\n",
                c.name, ratio, ratio <= 1.15 ? "met" : "NOT met", after_stable ? "yes" : "NO");
    std::fflush(stdout);
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  return 0;
}
