// The output files of `piece` and `scene` (app/cli/scene_outputs.h).
#include "app/cli/scene_outputs.h"

#include <chrono>
#include <filesystem>

#include <unistd.h>

#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "base/timer.h"
#include "export/pov_export.h"
#include "export/texture_image.h"
#include "npr/silhouettes.h"
#include "render/image/image.h"
#include "render/povray_runner.h"
#include "render/scene_preview.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

Format output_format(const std::string& option, const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".glb" || ext == ".gltf") return Format::Gltf;
  if (ext == ".pov") return Format::Pov;
  throw UsageError(option + ": '" + path + "' must end in .glb, .gltf or .pov");
}

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

GltfSceneOptions export_options(const std::string& compress, int lods, const std::string& textures,
                                bool texture_fallback) {
  GltfSceneOptions gltf;
  gltf.compression = parse_gltf_compression(compress);
  gltf.lods = lods;
  gltf.textures = parse_texture_format(textures);
  if (texture_fallback && gltf.textures != TextureFormat::Ktx2)
    throw UsageError("--texture-fallback: only with --textures ktx2 (it adds JPEG or PNG "
                     "beside the KTX2 images)");
  gltf.texture_fallback = texture_fallback;
  if (gltf.textures == TextureFormat::Ktx2) gltf.basisu = require_basisu("--textures ktx2");
  return gltf;
}

Written write_outputs(const SceneAssets& assets, const Targets& t, int threads, double silhouettes,
                      const GltfSceneOptions& gltf) {
  Written w;
  auto t0 = Clock::now();
  // Strokes are drawn in the preview and the POV-Ray scene; a glTF file has none.
  bool drawn = !t.png.given.empty() || !t.render.given.empty();
  for (const Target& out : t.exports)
    drawn = drawn || output_format("-o", out.given) != Format::Gltf;
  std::vector<Stroke> strokes;
  if (silhouettes > 0 && drawn) {
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

}  // namespace cutaway::cli
