// Interior volume benchmark and accuracy table: for every shipped template (the template's own
// model, no seed) at two voxel sizes (the skin's longest edge / 48 and / 96 by default), the
// volume's size, sampling time and file sizes, and its colours on random caps against PMVC at
// the same points (volume/volume_accuracy.h): mean and 99th percentile in steps of 1/255 of
// sRGB, away from surfaces and within one voxel of one, and the share of cap points on the
// wrong side of the outline. doc/algorithms.md §8 keeps the table and the default it chose.
//
// Run:   cmake --build build --target bench_volume && ./build/bench_volume
// Options: --across N[,N...] (voxels along the longest edge; default 48,96), --planes N (random
//          caps per template, default 6), --threads N (0: all cores), then template names to
//          run only those.
// One line per case; the last line gives the tomato's colour flipbook at the default against
// the 4 MB target.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "diffusion/diffusion.h"
#include "export/vdb_export.h"
#include "export/volume_flipbook.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "volume/interior_volume.h"
#include "volume/volume_accuracy.h"

namespace {

namespace fs = std::filesystem;

std::vector<int> parse_list(const char* text) {
  std::vector<int> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) values.push_back(std::atoi(item.c_str()));
  return values;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> across = {48, 96};
  int planes = 6, threads = 0;
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--across") && i + 1 < argc) across = parse_list(argv[++i]);
    else if (!std::strcmp(argv[i], "--planes") && i + 1 < argc) planes = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else only.emplace_back(argv[i]);
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(CUTAWAY_SOURCE_DIR) / "templates"))
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  double tomato_bytes = -1;
  std::printf("template across voxel_mm voxels solid regions classify_s pmvc_s colour_png_kb "
              "all_png_kb vdb_kb points near mean_far p99_far mean_near p99_near wrong_side_pct\n");
  for (const fs::path& file : files) {
    const std::string name = file.stem().string();
    if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
    const cutaway::Template tmpl = cutaway::load_template(file);
    const cutaway::DsModel model = cutaway::build_model(tmpl);
    cutaway::DiffusionOptions options;
    options.threads = threads;
    const auto diffusion = cutaway::make_cpu_diffusion(model, options);
    const std::vector<cutaway::Plane> caps = cutaway::random_cap_planes(model, planes, 1);
    for (int n : across) {
      const double voxel_m = cutaway::voxel_length_across(model, n);
      auto grid = cutaway::volume_grid(model, voxel_m);
      if (!grid) {
        std::printf("%s %d refused: %s\n", name.c_str(), n, grid.reason().c_str());
        continue;
      }
      const cutaway::InteriorVolume volume =
          cutaway::sample_interior_volume(model, *diffusion, std::move(*grid), threads);
      const auto flipbooks = cutaway::encode_flipbooks(volume);
      const double colour_kb = flipbooks ? flipbooks->colour.size() / 1e3 : -1;
      const double all_kb = flipbooks ? (flipbooks->colour.size() + flipbooks->structure.size() +
                                         flipbooks->material.size()) /
                                            1e3
                                      : -1;
      const double vdb_kb = cutaway::encode_vdb(volume, name, -1).size() / 1e3;
      const cutaway::VolumeErrors e =
          cutaway::volume_errors(model, *diffusion, volume, caps, threads);
      std::printf(
          "%s %d %.3f %zu %zu %u %.2f %.2f %.0f %.0f %.0f %zu %zu %.2f %.1f %.2f %.1f %.2f\n",
          name.c_str(), n, voxel_m * 1e3, volume.voxels(), volume.solid, volume.regions,
          volume.seconds_classify, volume.seconds_diffuse, colour_kb, all_kb, vdb_kb, e.points,
          e.near_points, e.mean_far, e.p99_far, e.mean_near, e.p99_near, 100 * e.wrong_side);
      std::fflush(stdout);
      if (name == "tomato" && n == cutaway::kDefaultVoxelsAcross) tomato_bytes = colour_kb * 1e3;
    }
  }
  if (tomato_bytes >= 0)
    std::printf("tomato colour flipbook at the default (%d across): %.2f MB (target: under 4 MB)\n",
                cutaway::kDefaultVoxelsAcross, tomato_bytes / 1e6);
  return 0;
}
