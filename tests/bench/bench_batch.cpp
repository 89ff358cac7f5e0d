// Batch throughput benchmark: the mixed batch batches/fruit-assets.yaml (tomato halves and
// wedges, kiwi halves and slices, persimmon wedges, with DS models and the sample's
// thumbnails) built as `cutaway batch` builds it, one variant at a time on one thread (the
// diffusion backend's threads = 1), so that the rate is per core: a farm of N cores makes
// about N times as many (the variant's time is shared evenly by its cuts). One line per
// template and cut: assets, seconds per asset, assets per
// hour per core, and where the time goes (variant, cut = sections + PMVC + clipping, texture
// bake, glTF export, thumbnail); then the whole batch.
//
// Run:   make bench   or:  cmake --build build --target bench_batch && ./build/bench_batch
// Options: --batch FILE (another batch file).
#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include "batch/batch_assets.h"
#include "diffusion/diffusion.h"
#include "io/batch_parser.h"
#include "render/image/image.h"
#include "render/scene_preview.h"

namespace {

struct Row {
  int assets = 0;
  cutaway::UnitTimings t;
  double total = 0;
};

void add(Row& row, const cutaway::UnitTimings& t) {
  row.t.variant += t.variant;
  row.t.cut += t.cut;
  row.t.bake += t.bake;
  row.t.export_glb += t.export_glb;
  row.t.thumbnail += t.thumbnail;
  row.total += t.variant + t.cut + t.bake + t.export_glb + t.thumbnail;
}

void print(const std::string& name, const Row& r) {
  const double per_asset = r.total / r.assets;
  std::printf("%-24s %6d %9.2f %12.0f %8.2f %8.2f %8.2f %8.2f %8.2f\n", name.c_str(), r.assets,
              per_asset, 3600.0 / per_asset, r.t.variant / r.assets, r.t.cut / r.assets,
              r.t.bake / r.assets, r.t.export_glb / r.assets, r.t.thumbnail / r.assets);
}

}  // namespace

int main(int argc, char** argv) {
  std::string file = std::string(CUTAWAY_SOURCE_DIR) + "/batches/fruit-assets.yaml";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--batch")) file = argv[i + 1];
    else {
      std::fprintf(stderr, "usage: bench_batch [--batch FILE]\n");
      return 2;
    }
  }
  const cutaway::Batch batch = cutaway::load_batch(file);
  const cutaway::BatchPlan plan = cutaway::plan_batch(batch, "bench");
  cutaway::BatchBuildOptions options;
  options.diffusion = [&](const cutaway::DsModel& model) {
    return cutaway::make_cpu_diffusion(model, {batch.export_options.cube, 1});
  };
  options.thumbnail = [](const cutaway::SceneAssets& assets) {
    return cutaway::encode_png(cutaway::render_scene_preview(assets));
  };
  std::map<std::string, Row> rows;  // "template cut"
  Row all;
  for (size_t u = 0; u < plan.units.size(); ++u) {
    for (const cutaway::BuiltAsset& b : cutaway::build_batch_unit(batch, plan, u, options)) {
      Row& row = rows[b.record.template_name + " " + b.record.cut];
      ++row.assets;
      add(row, b.seconds);
      ++all.assets;
      add(all, b.seconds);
    }
  }
  std::printf("%-24s %6s %9s %12s %8s %8s %8s %8s %8s\n", "assets (1 thread)", "count", "s/asset",
              "/hour/core", "variant", "cut", "bake", "export", "thumb");
  for (const auto& [name, row] : rows) print(name, row);
  print("mixed batch", all);
  return 0;
}
