// `cutaway scene`: the main job, a scene of cut objects as glTF or POV-Ray, its preview and its
// POV-Ray render. Argument checks and calls into the libraries only.
#include <chrono>
#include <filesystem>
#include <set>
#include <string>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "base/timer.h"
#include "cli/commands.h"
#include "cli/scene_outputs.h"
#include "export/texture_image.h"
#include "io/scene_parser.h"
#include "scene/scene_budget.h"
#include "scene/scene_builder.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

int run_scene(const SceneArgs& a, const Common& common, OutputSet& outputs) {
  if (a.outputs.empty()) throw UsageError("-o is required (.glb, .gltf or .pov)");
  for (const std::string& path : a.outputs) output_format("-o", path);
  if (!a.png.empty()) require_extension("--png", a.png, ".png");
  if (!a.render.empty()) require_extension("--render", a.render, ".png");
  const Targets targets = register_outputs(outputs, a.outputs, a.png, a.render);
  const auto t0 = Clock::now();
  const Scene scene = load_scene(a.scene_path);
  check_scene_model_vertices(scene);
  if (a.texels_per_mm > 0) {
    if (const std::string why = cap_texels_rule(scene_cut_area(scene), a.texels_per_mm);
        !why.empty())
      throw UsageError("--texels-per-mm: " + why);
  }
  const double t_parse = seconds_since(t0);
  const uint64_t seed = a.seed >= 0 ? static_cast<uint64_t>(a.seed) : scene.seed;
  const DiffusionFactory diffusion = diffusion_factory(a.cube, common);
  std::string backend_name;
  SceneBuildOptions options;
  options.sampling = common.sampling;
  options.cap_colours = a.colours == "vertex" ? CapColours::Vertex : CapColours::Texture;
  options.atlas.texels_per_m = 1000 * a.texels_per_mm;  // 0: the scene's
  options.atlas.power_of_two = options.skin.power_of_two = a.power_of_two;
  options.diffusion = [&](const DsModel& model) {
    auto backend = diffusion(model);
    backend_name = backend->name();
    return backend;
  };
  options.progress = [&](int done, int total, const std::string& line) {
    spdlog::info("[{}/{}] {}", done, total, line);
  };
  SceneStats st;
  const auto t1 = Clock::now();
  const SceneAssets assets = build_scene(scene, seed, options, &st);
  const double t_build = seconds_since(t1);
  if (st.placed < st.pieces)
    spdlog::warn("{} of {} pieces did not fit in the container and were left out",
                 st.pieces - st.placed, st.pieces);
  if (st.defective_pieces > 0)
    spdlog::warn("{} pieces are not closed 2-manifolds", st.defective_pieces);
  if (!st.settled)
    spdlog::warn("the pieces were still moving when settling stopped after {:.1f} simulated s",
                 st.simulated_seconds);
  if (st.lost > 0)
    spdlog::warn("{} pieces fell out of the container {} times and were left out", st.lost,
                 options.settle.max_redrops + 1);
  {
    const double limit = options.settle.stable_motion_m;
    const auto level = st.stability_motion_m > limit ? spdlog::level::warn : spdlog::level::info;
    spdlog::log(level,
                "stability check: re-simulated for {:g} s, the settled pieces moved at most "
                "{:.2f} mm (limit {:g} mm; {} checks)",
                options.settle.verify_seconds, 1000 * st.stability_motion_m, 1000 * limit,
                st.stability_checks);
  }
  spdlog::info("{}: {} objects, {} pieces placed, {} triangles (seed {})", scene.name,
               st.objects, st.placed, st.triangles, seed);
  // The textures of each .pov and .gltf go beside it, committed with it (a .pov and a .gltf
  // of one stem share them).
  std::set<std::string> texture_files;
  for (const Target& out : targets.exports)
    if (output_format("-o", out.given) == Format::Pov ||
        std::filesystem::path(out.given).extension() == ".gltf")
      for (const std::string& name :
           texture_file_names(out.given, assets, parse_texture_format(a.textures))) {
        const std::string file = (std::filesystem::path(out.given).parent_path() / name).string();
        if (texture_files.insert(file).second) outputs.add("-o", file);
      }
  const Written w =
      write_outputs(assets, targets, common.threads, scene.render.silhouettes,
                    export_options(a.compress, a.lods, a.textures));
  if (common.stats) {
    nlohmann::ordered_json j = {
        {"scene", scene.name},
        {"seed", seed},
        {"backend", backend_name},
        {"objects", st.objects},
        {"pieces", st.pieces},
        {"placed", st.placed},
        {"triangles", st.triangles},
        {"diffused_points", st.diffused.all},
        {"physics",
         {{"simulated_seconds", st.simulated_seconds},
          {"settled", st.settled},
          {"decomposed_pieces", st.decomposed_pieces},
          {"redropped", st.redropped},
          {"lost", st.lost},
          {"stability_motion_mm", 1000 * st.stability_motion_m},
          {"stability_checks", st.stability_checks}}},
        {"seconds",
         {{"parse", t_parse},
          {"build", t_build},
          {"variants", st.seconds_variants},
          {"backend_setup", st.seconds_backend},
          {"sections", st.seconds_sections},
          {"diffuse", st.seconds_diffuse},
          {"clip", st.seconds_clip},
          {"bake", st.seconds_bake},
          {"layout", st.seconds_layout},
          {"physics", st.seconds_physics},
          {"strokes", w.strokes_s},
          {"export", w.export_s},
          {"png", w.preview_s},
          {"povray", w.povray_s}}}};
    *common.stats = std::move(j);
  }
  return 0;
}

}  // namespace cutaway::cli
