// `cutaway scene`: the main job, a scene of cut objects as glTF or POV-Ray, its preview and its
// POV-Ray render. Argument checks and calls into the libraries only.
#include <chrono>
#include <filesystem>
#include <memory>
#include <set>
#include <string>

#include <nlohmann/json.hpp>
#include <oneapi/tbb/global_control.h>
#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "app/cli/scene_outputs.h"
#include "base/timer.h"
#include "diffusion/diffusion.h"
#include "export/engine_profile.h"
#include "export/texture_image.h"
#include "io/scene_parser.h"
#include "scene/scene_budget.h"
#include "scene/scene_builder.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// `cutaway scene SCENE [--seed S] -o OUT.glb|.gltf|.pov [-o ...] [--png preview.png]
/// [--render out.png]`: one build, any number of exports.
struct SceneArgs {
  std::string scene_path, png, render;
  std::vector<std::string> outputs;
  int64_t seed = -1;  ///< >= 0: overrides the scene's seed
  int cube = kDefaultCubeSize;
  std::string colours = "texture";  ///< "texture" or "vertex" (CapColours)
  double texels_per_mm = 0;         ///< CapAtlasOptions::texels_per_m / 1000; 0: the scene's
  bool power_of_two = false;        ///< --power-of-two: texture sides powers of two
  std::string compress;             ///< glTF vertex data: none, quantize or meshopt; empty: the
                                    ///< profile's, else quantize
  std::string engine;               ///< --for: an engine profile (engine_profile.h), empty: none
  int lods = 0;                     ///< glTF levels of detail per mesh (GltfSceneOptions)
  std::string textures = "jpeg";    ///< texture images: jpeg, png or ktx2 (TextureFormat)
  bool texture_fallback = false;    ///< --texture-fallback: JPEG/PNG beside KTX2
  StyleArgs style;                  ///< --style, --silhouettes: over the scene file's render
  CacheArgs cache;
};

/// Logs what went wrong or nearly so while building (pieces left out, not closed, not settled,
/// fallen out), the stability check, and the summary line.
void log_build(const Scene& scene, uint64_t seed, const SceneStats& st,
               const SettleOptions& settle) {
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
                 settle.max_redrops + 1);
  const double limit = settle.stable_motion_m;
  const auto level = st.stability_motion_m > limit ? spdlog::level::warn : spdlog::level::info;
  const std::string kept =
      st.stability_kept_check < st.stability_checks
          ? fmt::format(", the layout of check {} kept", st.stability_kept_check)
          : std::string();
  spdlog::log(level,
              "stability check: re-simulated for {:g} s, the settled pieces moved at most "
              "{:.2f} mm (limit {:g} mm; {} checks{})",
              settle.verify_seconds, 1000 * st.stability_motion_m, 1000 * limit,
              st.stability_checks, kept);
  spdlog::info("{}: {} objects, {} pieces placed, {} triangles (seed {})", scene.name, st.objects,
               st.placed, st.triangles, seed);
  if (st.cached_objects > 0)
    spdlog::info("{} of {} objects{} were read from the cut cache", st.cached_objects, st.objects,
                 st.cached_placements ? " and their placements" : "");
}

/// Registers the texture files of each .pov and .gltf output: they go beside it, committed with
/// it (a .pov and a .gltf of one stem share them; a .gltf's texture fallback has the names the
/// .pov's images have).
void register_texture_outputs(OutputSet& outputs, const Targets& targets, const SceneAssets& assets,
                              const GltfSceneOptions& gltf) {
  std::set<std::string> texture_files;
  const auto add = [&](const std::string& given, TextureFormat format) {
    for (const std::string& name : texture_file_names(given, assets, format)) {
      const std::string file = (std::filesystem::path(given).parent_path() / name).string();
      if (texture_files.insert(file).second) outputs.add("-o", file);
    }
  };
  for (const Target& out : targets.exports) {
    if (output_format("-o", out.given) == Format::Pov) {
      add(out.given, image_file_format(gltf.textures));
    } else if (std::filesystem::path(out.given).extension() == ".gltf") {
      add(out.given, gltf.textures);
      if (gltf.texture_fallback) add(out.given, image_file_format(gltf.textures));
    }
  }
}

/// The --stats of a scene: its counts, the physics and the seconds of each stage.
nlohmann::ordered_json scene_stats(const Scene& scene, uint64_t seed, const std::string& backend,
                                   const SceneStats& st, const CutCache* cache, double t_parse,
                                   double t_build, const Written& w) {
  return {{"scene", scene.name},
          {"seed", seed},
          {"backend", backend},
          {"objects", st.objects},
          {"pieces", st.pieces},
          {"placed", st.placed},
          {"triangles", st.triangles},
          {"diffused_points", st.diffused.all},
          {"cut_cache", cut_cache_stats(cache)},
          {"physics",
           {{"from_cut_cache", st.cached_placements},
            {"simulated_seconds", st.simulated_seconds},
            {"settled", st.settled},
            {"decomposed_pieces", st.decomposed_pieces},
            {"redropped", st.redropped},
            {"lost", st.lost},
            {"stability_motion_mm", 1000 * st.stability_motion_m},
            {"stability_checks", st.stability_checks},
            {"stability_kept_check", st.stability_kept_check}}},
          {"seconds",
           {{"parse", t_parse},
            {"build", t_build},
            {"variants", st.seconds_variants},
            {"backend_setup", st.seconds_backend},
            {"sections", st.seconds_sections},
            {"diffuse", st.seconds_diffuse},
            {"clip", st.seconds_clip},
            {"bake", st.seconds_bake},
            {"collision", st.seconds_collision},
            {"layout", st.seconds_layout},
            {"physics", st.seconds_physics},
            {"strokes", w.strokes_s},
            {"export", w.export_s},
            {"png", w.preview_s},
            {"povray", w.povray_s}}}};
}

int run_scene(const SceneArgs& a, const Common& given, OutputSet& outputs) {
  if (a.outputs.empty()) throw UsageError("-o is required (.glb, .gltf or .pov)");
  for (const std::string& path : a.outputs) output_format("-o", path);
  if (!a.png.empty()) require_extension("--png", a.png, ".png");
  if (!a.render.empty()) require_extension("--render", a.render, ".png");
  const Targets targets = register_outputs(outputs, a.outputs, a.png, a.render);
  const auto t0 = Clock::now();
  const Scene scene = load_scene(a.scene_path);
  check_scene_model_vertices(scene);
  if (a.texels_per_mm > 0) {
    if (const Check texels = check_cap_texels(scene_cut_area(scene), a.texels_per_mm); !texels)
      throw UsageError("--texels-per-mm: " + texels.reason());
  } else if (const std::string fitted = texel_fit_note(scene); !fitted.empty()) {
    spdlog::warn("{}: {}", a.scene_path, fitted);
  }
  GltfSceneOptions gltf = export_options("quantize", a.lods, a.textures, a.texture_fallback);
  if (!a.engine.empty()) apply_engine_profile(a.engine, gltf);  // then --compress over it
  if (!a.compress.empty()) gltf.compression = parse_gltf_compression(a.compress);
  const double t_parse = seconds_since(t0);
  const Common common = with_resolved_backend(given);  // probed once, not per use below
  const uint64_t seed = a.seed >= 0 ? static_cast<uint64_t>(a.seed) : scene.seed;
  const std::unique_ptr<CutCache> cache = open_cut_cache(a.cache);
  if (cache) gltf.texture_store = cache->blob_store();  // KTX2 encodings kept there too
  SceneBuildOptions options;
  options.cache = cache.get();
  options.diffusion_settings = diffusion_settings(a.cube, common);
  options.sampling = common.sampling;
  options.cap_colours = a.colours == "vertex" ? CapColours::Vertex : CapColours::Texture;
  options.atlas.texels_per_m = 1000 * a.texels_per_mm;  // 0: the scene's
  options.atlas.power_of_two = options.skin.power_of_two = a.power_of_two;
  options.diffusion = diffusion_factory(a.cube, common);
  if (resolved_backend(common) == "cpu")  // gl: one context, one thread
    options.objects_at_once = 2 * static_cast<int>(oneapi::tbb::global_control::active_value(
                                      oneapi::tbb::global_control::max_allowed_parallelism));
  options.progress = [&](int done, int total, const std::string& line) {
    spdlog::info("[{}/{}] {}", done, total, line);
  };
  SceneStats st;
  const auto t1 = Clock::now();
  const SceneAssets assets = build_scene(scene, seed, options, &st);
  const double t_build = seconds_since(t1);
  log_build(scene, seed, st, options.settle);
  register_texture_outputs(outputs, targets, assets, gltf);
  // The command line's style or strokes over the file's.
  const double strokes = a.style.silhouettes || !a.style.style.empty() ? stroke_strength(a.style)
                                                                       : scene.render.silhouettes;
  const Written w = write_outputs(assets, targets, common.threads, strokes, gltf);
  if (common.stats)
    *common.stats =
        scene_stats(scene, seed, resolved_backend(common), st, cache.get(), t_parse, t_build, w);
  return 0;
}

}  // namespace

Command add_scene_command(CLI::App& app) {
  auto args = std::make_shared<SceneArgs>();
  CLI::App* scene = app.add_subcommand(
      "scene", "the main job: a scene of cut objects as glTF or POV-Ray, and pictures of it");
  scene->add_option("SCENE", args->scene_path, "scene file (.yaml)")->required();
  scene->add_option("--seed", args->seed, "seed (default: the scene file's)")->check(seed_rule());
  scene
      ->add_option("-o,--output", args->outputs,
                   "scene to write: .glb, .gltf or .pov; repeat for several formats")
      ->required()
      ->allow_extra_args(false);
  scene->add_option("--png", args->png, "OpenGL preview (PNG)");
  scene->add_option("--render", args->render, "POV-Ray render (PNG)");
  scene->add_option("--cube", args->cube, "cube-map texels per face edge for PMVC")
      ->check(number_rule(2, 256));
  add_colours_option(scene, args->colours);
  add_style_options(scene, args->style, "over the PNG and in .pov (over the file's render)");
  scene
      ->add_option("--texels-per-mm", args->texels_per_mm,
                   "texel density of baked cut-face textures (default: the scene's "
                   "render.texels_per_mm, else 8.6: a 60 mm cut face 516 texels across)")
      ->check(number_rule(0.1, 100.0));
  scene->add_flag("--power-of-two", args->power_of_two,
                  "baked textures with sides powers of two (default: multiples of 4, fewer "
                  "texels)");
  add_export_options(scene, args->compress, args->lods, args->textures, args->texture_fallback);
  add_engine_option(scene, args->engine,
                    "the consumer the glTF file is for, which sets --compress (given wins), the "
                    "pieces' collision naming and pivots and whether the backdrop is written: "
                    "godot (float32, one RigidBody per piece, no backdrop), unreal (float32, "
                    "UCX_ hulls, no backdrop), unity (quantize, no backdrop), web (meshopt, no "
                    "backdrop) or blender (quantize); doc/engines.md");
  add_cache_options(scene, args->cache);
  return {scene, [args](const Common& common, OutputSet& outputs) {
            return run_scene(*args, common, outputs);
          }};
}

}  // namespace cutaway::cli
