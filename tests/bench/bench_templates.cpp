// The template library beside the paper's Table 1 (Takayama et al. 2010): for each of its
// thirteen models, the DS vertex and face counts of build_model, the template's size on disk
// (the YAML plus the PLY files it references) and the time of a typical cut: one cross-section
// through the middle of the object (the horizontal plane at mid-height of the DS model's
// bounds), meshed and coloured as `cutaway section` does (cpu backend, the default cube, size bound
// 3 x the template edge), best of N. The vertical cut through the axis is timed too. The BVH
// of the diffusion surfaces is built once per model and reported apart (bvh_s).
//
// Run:   make bench                       (builds and runs the `benchmarks` target)
//   or:  cmake --build build --target bench_templates && ./build/bench_templates
// Options: --threads N (0: all cores, default), --cube N (default kDefaultCubeSize), --repeat N
// (best of N,
//          default 3).
// The paper's figures come from tests/data/paper-table1.tsv. Its times are for a 2010 laptop (2.6
// GHz CPU, NVIDIA Quadro FX 570M); its sizes are of its model files, ours of the templates.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "diffusion/diffusion.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "paper_table1.h"
#include "section/cross_section.h"

namespace {

using namespace cutaway::bench;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Bytes of the template file plus every distinct mesh file its surfaces reference.
uintmax_t size_on_disk(const cutaway::Template& t) {
  std::set<fs::path> files{fs::weakly_canonical(t.file)};
  for (const auto& s : t.surfaces)
    if (!s.mesh_file.empty()) files.insert(fs::weakly_canonical(s.mesh_file));
  uintmax_t bytes = 0;
  for (const fs::path& f : files) bytes += fs::file_size(f);
  return bytes;
}

std::string symmetry_text(const cutaway::Template& t) {
  switch (t.symmetry) {
    case cutaway::Symmetry::Cylindrical: return "cylindrical";
    case cutaway::Symmetry::NFold: return std::to_string(t.folds) + "-fold";
    default: return "none";
  }
}

/// Best of `repeat` timings of one cross-section with `plane`.
double time_cut(const cutaway::DsModel& model, const cutaway::Plane& plane,
                const cutaway::DiffusionBackend& backend, double edge_m, int repeat,
                size_t* section_vertices) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = Clock::now();
    const cutaway::CrossSection cs =
        *cutaway::make_cross_section(model, plane, backend, cutaway::CrossSectionOptions{edge_m});
    best = std::min(best, seconds_since(t0));
    *section_vertices = cs.position.size();
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0, cube = cutaway::DiffusionOptions{}.cube_size, repeat = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (a == "--cube" && i + 1 < argc) cube = std::atoi(argv[++i]);
    else if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
    else {
      std::fprintf(stderr, "usage: bench_templates [--threads N] [--cube N] [--repeat N]\n");
      return 2;
    }
  }
  std::string source;
  const std::vector<PaperRow> table1 = read_table1(&source);
  const unsigned cores = std::thread::hardware_concurrency();
  std::printf("# bench_templates: cpu backend, cube %d, %d threads (%u cores), best of %d; "
              "cut_s: the horizontal cross-section at mid-height (triangulation + PMVC, BVH "
              "built: bvh_s); paper: %s\n",
              cube, threads > 0 ? threads : static_cast<int>(cores), cores, repeat, source.c_str());
  std::printf("%-11s %-11s %8s %8s %9s %7s %7s %7s | %-11s %8s %8s %9s %7s\n", "template",
              "symmetry", "vertices", "faces", "size_kb", "bvh_s", "cut_s", "vcut_s", "paper_sym",
              "vertices", "faces", "size_kb", "cut_s");
  int missing = 0;
  for (const PaperRow& paper : table1) {
    const fs::path path = fs::path(CUTAWAY_SOURCE_DIR) / "templates" / (paper.title + ".yaml");
    if (!fs::exists(path)) {
      std::printf("%-11s (no template)\n", paper.title.c_str());
      ++missing;
      continue;
    }
    const cutaway::Template tmpl = cutaway::load_template(path.string());
    const cutaway::DsModel model = cutaway::build_model(tmpl);
    const auto t_bvh = Clock::now();
    const auto cpu = cutaway::make_cpu_diffusion(model, {cube, threads});
    const double bvh_s = seconds_since(t_bvh);
    const glm::dvec3 mid = 0.5 * (model.bbox_min + model.bbox_max);
    size_t hv = 0, vv = 0;
    const double cut_s =
        time_cut(model, {{0, mid.y, 0}, {0, 1, 0}}, *cpu, tmpl.edge_m, repeat, &hv);
    const double vcut_s =
        time_cut(model, {{mid.x, 0, 0}, {1, 0, 0}}, *cpu, tmpl.edge_m, repeat, &vv);
    std::printf("%-11s %-11s %8zu %8zu %9.1f %7.3f %7.3f %7.3f | %-11s %8s %8s %9s %7s\n",
                tmpl.name.c_str(), symmetry_text(tmpl).c_str(), model.vertex_count(),
                model.face_count(), size_on_disk(tmpl) / 1024.0, bvh_s, cut_s, vcut_s,
                paper.symmetry.c_str(), paper.vertices.c_str(), paper.faces.c_str(),
                paper.size_kb.c_str(), paper.cut_s.c_str());
    std::fflush(stdout);
  }
  return missing ? 1 : 0;
}
