// Variant benchmark: for every shipped template, random variants as `cutaway variants` makes
// them (make_variant: vary the horizontal curves, build_model, scatter_grains), seeds 0, 1, ...
// One line per template: variants/s (single thread, as the CLI builds one variant at a time)
// and the DS faces of the variants with their grains (mean, min, max).
//
// Run:   make bench                       (builds and runs the `benchmarks` target)
//   or:  cmake --build build --target bench_variants && ./build/bench_variants
// Options: --seconds S (time per template, default 2), --max N (at most N variants per
//          template, default 50).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "io/template_parser.h"
#include "variation/variation.h"

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

}  // namespace

int main(int argc, char** argv) {
  double budget_s = 2.0;
  int max_variants = 50;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--seconds")) budget_s = std::stod(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--max")) max_variants = std::max(1, std::stoi(argv[i + 1]));
    else {
      std::fprintf(stderr, "usage: bench_variants [--seconds S] [--max N]\n");
      return 2;
    }
  }
  std::vector<fs::path> templates;
  for (const auto& e : fs::directory_iterator(fs::path(CUTAWAY_SOURCE_DIR) / "templates"))
    if (e.path().extension() == ".yaml") templates.push_back(e.path());
  std::sort(templates.begin(), templates.end());

  std::printf("%-10s %8s %10s %10s %10s %10s %8s\n", "template", "variants", "variants/s", "faces",
              "faces min", "faces max", "draws");
  for (const fs::path& path : templates) {
    const cutaway::Template tmpl = cutaway::load_template(path.string());
    int n = 0, draws = 0;
    size_t faces_sum = 0, faces_min = SIZE_MAX, faces_max = 0;
    const auto t0 = Clock::now();
    double elapsed = 0;
    while (n < max_variants && (n == 0 || elapsed < budget_s)) {
      const cutaway::Variant v = cutaway::make_variant(tmpl, static_cast<uint64_t>(n));
      const size_t faces = v.model.face_count();
      faces_sum += faces;
      faces_min = std::min(faces_min, faces);
      faces_max = std::max(faces_max, faces);
      draws += v.draws;
      ++n;
      elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    }
    std::printf("%-10s %8d %10.2f %10zu %10zu %10zu %8.2f\n", tmpl.name.c_str(), n, n / elapsed,
                faces_sum / static_cast<size_t>(n), faces_min, faces_max,
                static_cast<double>(draws) / n);
  }
  return 0;
}
