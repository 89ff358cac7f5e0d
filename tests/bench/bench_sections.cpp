// Cross-section benchmark: for every shipped template, a horizontal cut at mid-height and a
// vertical cut through the axis, meshed and coloured as `cutaway section` does (cpu backend,
// the default cube with adaptive directions, size bound 3 x the template edge), next to the paper's
// Table 1, to the same points with every texel of the cube cast, and to the sheet ray casting
// alone for every texel's ray (no colour work), with Embree's own float hits (embree_rays_per_s,
// cutaway 0.1's) and with the decided hits the backend uses (decided_rays_per_s): pmvc/embree
// compares rays per second, decided/embree what deciding hits on every CPU alike costs.
//
// Run:   make bench                       (builds and runs the `benchmarks` target)
//   or:  cmake --build build --target bench_sections && ./build/bench_sections
// Options: --threads N (0: all cores, default), --cube N (default: the CLI default,
// kDefaultCubeSize), --repeat N (best of N
//          timings per cut, default 3), --gl (also time the GL backend, its agreement with the
//          cpu backend in steps of 1/255, and whole cuts with it, dense and adaptive; slow on
//          llvmpipe).
// One line per case; the last line compares the tomato's cut with the target of 0.6 s.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "base/colour.h"
#include "diffusion/cube_directions.h"
#include "diffusion/diffusion.h"
#include "diffusion/diffusion_sheets.h"
#include "diffusion/sheet_rays.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "paper_table1.h"
#include "render/gl/pmvc_gl.h"
#include "section/cross_section.h"

namespace {

using namespace cutaway::bench;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Forwards to a backend and adds up the points and the time of its diffusions (adaptive
/// sampling diffuses a cut in several batches).
class TimedBackend final : public cutaway::DiffusionBackend {
 public:
  explicit TimedBackend(const cutaway::DiffusionBackend& inner) : inner_(inner) {}
  void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                        std::span<glm::dvec2> material) const override {
    const auto t0 = Clock::now();
    inner_.diffuse_channels(points, colour, material);
    seconds += seconds_since(t0);
    all_points.insert(all_points.end(), points.begin(), points.end());
  }
  std::string name() const override { return inner_.name(); }
  size_t rays_cast() const override { return inner_.rays_cast(); }
  mutable double seconds = 0;
  mutable std::vector<glm::dvec3> all_points;

 private:
  const cutaway::DiffusionBackend& inner_;
};

/// The sheet ray casting alone: the sheets of the cpu backend, packets of 16 directions of one
/// point, TBB over points with the same grain, summing only the hit distances. `Decided` is the
/// backend's own (SheetRayCaster: grown triangles, every proposal decided in double
/// precision), `EmbreeFloat` Embree's own hits on the same BVH settings (cutaway 0.1's).
class RawEmbree {
 public:
  RawEmbree(const cutaway::DsModel& model, int threads, cutaway::SheetHits hits)
      : threads_(threads), sheets_(cutaway::make_diffusion_sheets(model)),
        caster_(sheets_, threads, hits) {}

  /// Seconds to trace every direction of `dirs` from every point.
  double trace(const std::vector<glm::dvec3>& points, const cutaway::CubeDirections& dirs) {
    std::vector<double> sums(points.size(), 0.0);
    auto body = [&](const oneapi::tbb::blocked_range<size_t>& range) {
      for (size_t i = range.begin(); i != range.end(); ++i) sums[i] = trace_point(points[i], dirs);
    };
    const auto t0 = Clock::now();
    if (threads_ > 0) {
      oneapi::tbb::task_arena arena(threads_);
      arena.execute([&] {
        oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<size_t>(0, points.size(), 4), body);
      });
    } else {
      oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<size_t>(0, points.size(), 4), body);
    }
    const double s = seconds_since(t0);
    double total = 0;
    for (double x : sums) total += x;
    checksum_ += total;
    return s;
  }
  double checksum() const { return checksum_; }

 private:
  double trace_point(const glm::dvec3& x, const cutaway::CubeDirections& dirs) const {
    thread_local std::vector<cutaway::SheetHit> hits;
    hits.resize(dirs.direction.size());
    caster_.cast(x, dirs.direction, hits);
    double sum = 0;
    for (const cutaway::SheetHit& h : hits)
      if (h.sheet >= 0) sum += h.at.t;
    return sum;
  }

  int threads_;
  std::vector<cutaway::DiffusionSheet> sheets_;
  cutaway::SheetRayCaster caster_;
  double checksum_ = 0;
};

/// Best-of-`repeat` seconds of diffusing `points` with colours only and with colours and
/// material channels (one ray cast per direction either way).
std::pair<double, double> colour_and_material_seconds(const cutaway::DiffusionBackend& backend,
                                                      const std::vector<glm::dvec3>& points,
                                                      int repeat) {
  std::vector<glm::dvec3> colour(points.size());
  std::vector<glm::dvec2> material(points.size());
  double alone = 1e300, both = 1e300;
  for (int r = 0; r < repeat; ++r) {
    auto t0 = Clock::now();
    backend.diffuse_channels(points, colour, {});
    alone = std::min(alone, seconds_since(t0));
    t0 = Clock::now();
    backend.diffuse_channels(points, colour, material);
    both = std::min(both, seconds_since(t0));
  }
  return {alone, both};
}

/// How far the colours and material channels of two backends lie apart at the same points, in
/// steps of 1/255 (colour.h visible_difference).
struct Agreement {
  double mean = 0, max = 0;
};

Agreement agreement(const cutaway::DiffusionBackend& a, const cutaway::DiffusionBackend& b,
                    const std::vector<glm::dvec3>& points) {
  std::vector<glm::dvec3> colour_a(points.size()), colour_b(points.size());
  std::vector<glm::dvec2> material_a(points.size()), material_b(points.size());
  a.diffuse_channels(points, colour_a, material_a);
  b.diffuse_channels(points, colour_b, material_b);
  Agreement result;
  for (size_t i = 0; i < points.size(); ++i) {
    const double d =
        cutaway::visible_difference(colour_a[i], material_a[i], colour_b[i], material_b[i]);
    result.mean += d / static_cast<double>(points.size());
    result.max = std::max(result.max, d);
  }
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 0, cube = cutaway::DiffusionOptions{}.cube_size, repeat = 3;
  bool gl = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (a == "--cube" && i + 1 < argc) cube = std::atoi(argv[++i]);
    else if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--gl") gl = true;
    else {
      std::fprintf(stderr, "usage: bench_sections [--threads N] [--cube N] [--repeat N] [--gl]\n");
      return 2;
    }
  }
  std::string table1_source;
  const std::vector<PaperRow> table1 = read_table1(&table1_source);
  std::vector<fs::path> templates;
  for (const auto& e : fs::directory_iterator(fs::path(CUTAWAY_SOURCE_DIR) / "templates"))
    if (e.path().extension() == ".yaml") templates.push_back(e.path());
  std::sort(templates.begin(), templates.end());
  const unsigned cores = std::thread::hardware_concurrency();
  std::printf("# bench_sections: cpu backend, cube %d, %d threads (%u cores), best of %d; "
              "cut_s = triangulation + PMVC with the BVH built (bvh_s: once per model)\n",
              cube, threads > 0 ? threads : static_cast<int>(cores), cores, repeat);
  double tomato_cut = -1, checksum = 0;
  const cutaway::CubeDirections dirs = cutaway::make_cube_directions(cube);
  for (const fs::path& path : templates) {
    const cutaway::Template tmpl = cutaway::load_template(path.string());
    const cutaway::DsModel model = cutaway::build_model(tmpl);
    const auto t_bvh = Clock::now();
    // As `cutaway section` (app/cli/main.cpp run_section): DiffusionOptions{cube,
    // threads} and CrossSectionOptions{template edge} (size bound 3 x the edge). `every_texel`
    // casts every texel of the cube, the rays of Embree's raw loop, on the same points.
    const auto cpu = cutaway::make_cpu_diffusion(model, {cube, threads});
    const double bvh_s = seconds_since(t_bvh);
    const auto every_texel = cutaway::make_cpu_diffusion(model, {cube, threads, true, false});
    RawEmbree decided(model, threads, cutaway::SheetHits::Decided),
        raw(model, threads, cutaway::SheetHits::EmbreeFloat);
    std::unique_ptr<cutaway::DiffusionBackend> gl_backend;
    if (gl) gl_backend = cutaway::make_gl_diffusion(model, {cube, threads});
    const PaperRow* row = find_row(table1, tmpl.name);
    const std::vector<std::string> paper =
        row ? std::vector<std::string>{row->cut_s, row->vertices, row->faces}
            : std::vector<std::string>{"-", "-", "-"};
    const double mid = 0.5 * (model.bbox_min.y + model.bbox_max.y);
    const struct {
      const char* name;
      cutaway::Plane plane;
    } cuts[] = {{"horizontal", {{0, mid, 0}, {0, 1, 0}}}, {"vertical", {{0, 0, 0}, {1, 0, 0}}}};
    for (const auto& cut : cuts) {
      double cut_s = 1e300, diffuse_s = 1e300, raw_s = 1e300, decided_s = 1e300;
      size_t cut_rays = 0;
      cutaway::CrossSection cs;
      std::vector<glm::dvec3> points;
      for (int r = 0; r < repeat; ++r) {
        TimedBackend timed(*cpu);
        const size_t rays_before = cpu->rays_cast();
        const auto t0 = Clock::now();
        cs = *cutaway::make_cross_section(model, cut.plane, timed,
                                          cutaway::CrossSectionOptions{tmpl.edge_m});
        cut_s = std::min(cut_s, seconds_since(t0));
        cut_rays = cpu->rays_cast() - rays_before;
        diffuse_s = std::min(diffuse_s, timed.seconds);
        points = timed.all_points;
        raw_s = std::min(raw_s, raw.trace(points, dirs));
        decided_s = std::min(decided_s, decided.trace(points, dirs));
      }
      // Rays of the last cut's diffusion; Embree's raw loop casts every texel.
      const double rays = static_cast<double>(cut_rays);
      const double every_rays = static_cast<double>(points.size()) * dirs.direction.size();
      const auto [colour_s, material_s] = colour_and_material_seconds(*cpu, points, repeat);
      const auto [every_colour_s, every_s] =
          colour_and_material_seconds(*every_texel, points, repeat);
      const Agreement vs_every = agreement(*cpu, *every_texel, points);
      std::printf(
          "%-9s %-10s cpu adaptive directions: rays_per_point=%.0f of %zu pmvc_s=%.3f, every "
          "texel %.3f: %.2fx less; vs_every_texel_mean=%.3f/255 max=%.2f/255\n",
          tmpl.name.c_str(), cut.name, rays / points.size(), dirs.direction.size(), material_s,
          every_s, every_s / material_s, vs_every.mean, vs_every.max);
      std::printf("%-9s %-10s cpu colour_s=%.3f colour_and_material_s=%.3f material_cost=%+.1f%% "
                  "(target <= +15%%)\n",
                  tmpl.name.c_str(), cut.name, colour_s, material_s,
                  100 * (material_s / colour_s - 1));
      std::printf("%-9s %-10s ds_vertices=%zu ds_faces=%zu paper_vertices=%s paper_faces=%s "
                  "paper_cut_s=%s bvh_s=%.3f cut_s=%.3f triangulate_s=%.3f pmvc_s=%.3f "
                  "section_vertices=%zu pmvc_points=%zu rays=%.3g pmvc_rays_per_s=%.3g "
                  "embree_rays_per_s=%.3g pmvc/embree=%.2f decided_rays_per_s=%.3g "
                  "decided/embree=%.2f\n",
                  tmpl.name.c_str(), cut.name, model.vertex_count(), model.face_count(),
                  paper[1].c_str(), paper[2].c_str(), paper[0].c_str(), bvh_s, cut_s,
                  cut_s - diffuse_s, diffuse_s, cs.position.size(), points.size(), rays,
                  rays / diffuse_s, every_rays / raw_s, (rays / diffuse_s) / (every_rays / raw_s),
                  every_rays / decided_s, raw_s / decided_s);
      if (gl_backend) {
        const auto [gl_colour_s, gl_s] = colour_and_material_seconds(*gl_backend, points, repeat);
        const Agreement agree = agreement(*gl_backend, *cpu, points);
        std::printf(
            "%-9s %-10s gl pmvc_points=%zu pmvc_s=%.4f gl_rays_per_s=%.3g "
            "colour_s=%.4f material_cost=%+.1f%% vs_cpu_mean=%.3f/255 vs_cpu_max=%.2f/255\n",
            tmpl.name.c_str(), cut.name, points.size(), gl_s, rays / gl_s, gl_colour_s,
            100 * (gl_s / gl_colour_s - 1), agree.mean, agree.max);
        // Whole cuts (triangulation on the CPU, PMVC on the GL backend) in both samplings.
        for (const auto sampling : {cutaway::CapSampling::Dense, cutaway::CapSampling::Adaptive}) {
          cutaway::CrossSectionOptions options{tmpl.edge_m};
          options.sampling = sampling;
          double gl_cut_s = 1e300, gl_pmvc_s = 1e300;
          size_t diffused = 0;
          for (int r = 0; r < repeat; ++r) {
            const auto t0 = Clock::now();
            const cutaway::CrossSection gl_cs =
                *cutaway::make_cross_section(model, cut.plane, *gl_backend, options);
            gl_cut_s = std::min(gl_cut_s, seconds_since(t0));
            gl_pmvc_s = std::min(gl_pmvc_s, gl_cs.seconds_diffuse);
            diffused = gl_cs.diffused.all;
          }
          std::printf("%-9s %-10s gl %s cut_s=%.4f pmvc_s=%.4f diffused_points=%zu\n",
                      tmpl.name.c_str(), cut.name,
                      sampling == cutaway::CapSampling::Dense ? "dense" : "adaptive", gl_cut_s,
                      gl_pmvc_s, diffused);
        }
      }
      if (tmpl.name == "tomato") tomato_cut = std::max(tomato_cut, cut_s);
      std::fflush(stdout);
    }
    checksum += raw.checksum() + decided.checksum();
  }
  if (tomato_cut >= 0) {
    std::printf("target: tomato cut <= 0.6 s on 2 cores: slowest tomato cut %.3f s on %d "
                "threads: %s\n",
                tomato_cut, threads > 0 ? threads : static_cast<int>(cores),
                tomato_cut <= 0.6 ? "met" : "NOT met");
    std::fflush(stdout);
  }
  std::fprintf(stderr, "(sum of Embree hit distances, keeps the raw loop honest: %.6g)\n",
               checksum);
  return 0;
}
