// `cutaway piece` and `cutaway scene`: the cut pieces of one object, and whole scenes (the main
// job). Argument checks and calls into the libraries only.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>
#include <stdexcept>

#include <unistd.h>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "base/atomic_file.h"
#include "base/timer.h"
#include "cli/commands.h"
#include "export/gltf_export.h"
#include "export/pov_export.h"
#include "export/texture_image.h"
#include "io/scene_parser.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "npr/colour_modulation.h"
#include "npr/silhouettes.h"
#include "pieces/pieces.h"
#include "render/diffusion_backends.h"
#include "render/image/image.h"
#include "render/model_preview.h"
#include "render/povray_runner.h"
#include "render/scene_preview.h"
#include "scene/physics_settle.h"
#include "scene/piece_views.h"
#include "scene/scene_builder.h"
#include "variation/variation.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

enum class Format { Gltf, Pov };

/// The format an output path asks for (.glb, .gltf or .pov).
Format output_format(const std::string& option, const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".glb" || ext == ".gltf") return Format::Gltf;
  if (ext == ".pov") return Format::Pov;
  throw UsageError(option + ": '" + path + "' must end in .glb, .gltf or .pov");
}

/// One output file: the path as the user gave it (for messages and the format) and where to
/// write it (OutputSet::add()'s staging path).
struct Target {
  std::string given;
  std::filesystem::path file;
};

/// The outputs of `piece` and `scene`, registered in `outputs` before any work: each of
/// `paths` (-o; a .gltf with the .bin beside it), `png` and `render` when given.
struct Targets {
  std::vector<Target> exports;
  Target png, render;
};
Targets register_outputs(OutputSet& outputs, const std::vector<std::string>& paths,
                         const std::string& png, const std::string& render) {
  Targets t;
  for (const std::string& path : paths) {
    t.exports.push_back({path, outputs.add("-o", path)});
    if (std::filesystem::path(path).extension() == ".gltf") {
      std::filesystem::path bin(path);
      outputs.add("-o", bin.replace_extension(".bin").string());  // written beside the .gltf
    }
  }
  if (!png.empty()) t.png = {png, outputs.add("--png", png)};
  if (!render.empty()) t.render = {render, outputs.add("--render", render)};
  return t;
}

/// The glTF options of `--compress`, `--lods` and `--textures` (the texture format serves
/// the .pov files' images too).
GltfSceneOptions export_options(const std::string& compress, int lods,
                                const std::string& textures) {
  GltfSceneOptions gltf;
  gltf.compression = parse_gltf_compression(compress);
  gltf.lods = lods;
  gltf.textures = parse_texture_format(textures);
  return gltf;
}

/// Writes `assets` as each of `t.exports` (glTF or POV-Ray by extension), `t.png` (OpenGL
/// preview) and `t.render` (POV-Ray), each when asked for; glTF as `gltf` says, POV-Ray with
/// its textures in gltf.textures' format. Returns the seconds spent on each.
/// With `silhouettes` > 0, silhouette strokes of that strength (extract_strokes() at the
/// assets' image size) are drawn over the PNG and written into the POV-Ray files.
struct Written {
  double strokes_s = 0, export_s = 0, preview_s = 0, povray_s = 0;
  size_t strokes = 0;
};
Written write_outputs(const SceneAssets& assets, const Targets& t, int threads, double silhouettes,
                      const GltfSceneOptions& gltf) {
  Written w;
  auto t0 = Clock::now();
  std::vector<Stroke> strokes;
  if (silhouettes > 0) {
    StrokeOptions so;
    so.strength = silhouettes;
    strokes = extract_strokes(assets, so);
    w.strokes = strokes.size();
    w.strokes_s = seconds_since(t0);
    spdlog::info("{} silhouette strokes ({:.2f} s)", strokes.size(), w.strokes_s);
  }
  const std::vector<Stroke>* stroke_ptr = strokes.empty() ? nullptr : &strokes;
  t0 = Clock::now();
  std::filesystem::path pov_written;
  for (const Target& out : t.exports) {
    if (output_format("-o", out.given) == Format::Gltf) {
      write_scene_gltf(out.file, assets, gltf);
    } else {
      write_scene_pov(out.file, assets, stroke_ptr, gltf.textures);
      pov_written = out.file;
    }
    spdlog::info("wrote {}", out.given);
  }
  w.export_s = seconds_since(t0);
  if (!t.png.given.empty()) {
    t0 = Clock::now();
    ScenePreviewOptions preview;
    preview.strokes = stroke_ptr;
    write_png(t.png.file, render_scene_preview(assets, preview));
    spdlog::info("wrote {}", t.png.given);
    w.preview_s = seconds_since(t0);
  }
  if (!t.render.given.empty()) {
    t0 = Clock::now();
    // POV-Ray renders a .pov file: the one written, or a temporary one with its textures in
    // a temporary folder.
    std::filesystem::path pov = pov_written;
    std::filesystem::path temp;
    RemoveOnSignal temp_guard;
    if (pov_written.empty()) {
      temp = std::filesystem::temp_directory_path() /
             ("cutaway-" + std::to_string(::getpid()) + "-render");
      std::filesystem::create_directory(temp);
      temp_guard = RemoveOnSignal(temp, RemoveOnSignal::Kind::Folder);
      pov = temp / (asset_name(assets.name) + ".pov");
    }
    PovrayOptions options;
    options.threads = threads;
    try {
      if (!temp.empty()) write_scene_pov(pov, assets, stroke_ptr, gltf.textures);
      spdlog::info("rendering {} with POV-Ray at {} x {}", t.render.given, assets.width,
                   assets.height);
      render_povray(pov, t.render.file, assets.width, assets.height, options);
    } catch (...) {
      if (!temp.empty()) std::filesystem::remove_all(temp);
      throw;
    }
    if (!temp.empty()) std::filesystem::remove_all(temp);
    spdlog::info("wrote {}", t.render.given);
    w.povray_s = seconds_since(t0);
  }
  return w;
}

}  // namespace

CutSpec checked_cut(const Template& tmpl, const std::string& text, const std::string& what) {
  CutSpec cut;
  try {
    cut = parse_cut_spec(text, tmpl.metres_per_unit);
  } catch (const std::invalid_argument& e) {
    throw UsageError(what + ": " + e.what());
  }
  const long long estimate = estimate_piece_count(cut, template_extents(tmpl));
  if (estimate > kMaxPiecesPerCut)
    throw UsageError(what + ": would make about " + std::to_string(estimate) +
                     " pieces (at most " + std::to_string(kMaxPiecesPerCut) + ")");
  return cut;
}

PieceSet cut_object(const DsModel& model, const Template& tmpl, const CutSpec& cut, int cube,
                    const Common& common, double perlin, uint64_t seed, const std::string& what,
                    std::string* backend_name) {
  const auto diffusion =
      make_diffusion(model, {cube, common.threads}, parse_diffusion_choice(common.backend));
  if (backend_name) *backend_name = diffusion->name();
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  options.section.sampling = common.sampling;
  Outcome<PieceSet> made = cut_pieces(model, cut, *diffusion, options);
  if (!made) throw UsageError(what + ": " + made.reason());
  PieceSet set = std::move(*made);
  for (Piece& p : set.pieces)
    for (PiecePart& part : p.parts) modulate_colours(part.mesh, tmpl.npr, perlin, seed);
  return set;
}

int run_piece(const PieceArgs& a, const Common& common, OutputSet& outputs) {
  if (a.output.empty() && a.png.empty()) throw UsageError("give -o and/or --png");
  if (!a.output.empty()) output_format("-o", a.output);
  if (!a.png.empty()) require_extension("--png", a.png, ".png");
  std::vector<std::string> exports;
  if (!a.output.empty()) exports.push_back(a.output);
  const Targets targets = register_outputs(outputs, exports, a.png, "");
  const auto t0 = Clock::now();
  const Template tmpl = load_template(a.template_path);
  const CutSpec cut = checked_cut(tmpl, a.cut, "--cut " + quoted(a.cut));
  const DsModel model =
      a.seed >= 0 ? make_variant(tmpl, static_cast<uint64_t>(a.seed)).model : build_model(tmpl);
  const double t_model = seconds_since(t0);
  const auto t1 = Clock::now();
  // Perlin colour modulation in the object frame: the variant's seed, or 0 for the template.
  std::string backend_name;
  const PieceSet set = cut_object(model, tmpl, cut, a.cube, common, a.perlin,
                                  a.seed >= 0 ? static_cast<uint64_t>(a.seed) : 0,
                                  "--cut " + quoted(a.cut), &backend_name);
  const double t_cut = seconds_since(t1);
  size_t triangles = 0;
  for (const Piece& p : set.pieces)
    for (const PiecePart& part : p.parts) triangles += part.mesh.triangle.size();
  spdlog::info("{}: {} pieces, {} triangles, {} cut planes", tmpl.name, set.pieces.size(),
               triangles, set.cells.planes.size());
  if (set.attempts > 1)
    spdlog::info("the cut was redone {} times with its planes nudged (near-degenerate position)",
                 set.attempts - 1);
  if (set.defective_pieces > 0)
    spdlog::warn("{} pieces are not closed 2-manifolds", set.defective_pieces);
  const SceneAssets assets =
      piece_assets(set, tmpl.name, tmpl.skin_material, tmpl.cut_material, 0.3, a.width, a.height);
  const Written w =
      write_outputs(assets, targets, common.threads, a.silhouettes,
                    export_options(a.compress, a.lods, a.textures));
  if (common.stats) {
    print_stats({{"template", tmpl.name},
                 {"backend", backend_name},
                 {"pieces", set.pieces.size()},
                 {"planes", set.cells.planes.size()},
                 {"triangles", triangles},
                 {"diffused_points", set.diffused_points},
                 {"seconds",
                  {{"model", t_model},
                   {"cut", t_cut},
                   {"sections", set.seconds_sections},
                   {"diffuse", set.seconds_diffuse},
                   {"clip", set.seconds_clip},
                   {"strokes", w.strokes_s},
                   {"export", w.export_s},
                   {"png", w.preview_s}}}});
  }
  return 0;
}

int run_scene(const SceneArgs& a, const Common& common, OutputSet& outputs) {
  if (a.outputs.empty()) throw UsageError("-o is required (.glb, .gltf or .pov)");
  for (const std::string& path : a.outputs) output_format("-o", path);
  if (!a.png.empty()) require_extension("--png", a.png, ".png");
  if (!a.render.empty()) require_extension("--render", a.render, ".png");
  const Targets targets = register_outputs(outputs, a.outputs, a.png, a.render);
  const auto t0 = Clock::now();
  const Scene scene = load_scene(a.scene_path);
  const double t_parse = seconds_since(t0);
  const uint64_t seed = a.seed >= 0 ? static_cast<uint64_t>(a.seed) : scene.seed;
  const DiffusionChoice choice = parse_diffusion_choice(common.backend);
  std::string backend_name;
  SceneBuildOptions options;
  options.sampling = common.sampling;
  options.cap_colours = a.colours == "vertex" ? CapColours::Vertex : CapColours::Texture;
  options.atlas.texels_per_m = 1000 * a.texels_per_mm;  // 0: the scene's
  options.diffusion = [&](const DsModel& model) {
    auto backend = make_diffusion(model, {a.cube, common.threads}, choice);
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
    const nlohmann::ordered_json j = {
        {"scene", scene.name},
        {"seed", seed},
        {"backend", backend_name},
        {"objects", st.objects},
        {"pieces", st.pieces},
        {"placed", st.placed},
        {"triangles", st.triangles},
        {"diffused_points", st.diffused_points},
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
    print_stats(j);
  }
  return 0;
}

}  // namespace cutaway::cli
