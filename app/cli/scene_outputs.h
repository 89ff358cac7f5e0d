// What the `piece` and `scene` commands share: their output files (-o in glTF or POV-Ray,
// --png, --render), registered before any work and written from one SceneAssets.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "assets/scene_assets.h"
#include "base/atomic_file.h"
#include "export/gltf_export.h"

namespace cutaway::cli {

enum class Format { Gltf, Pov };

/// The format an output path asks for (.glb, .gltf or .pov).
/// @throws UsageError "OPTION: 'PATH' must end in .glb, .gltf or .pov"
Format output_format(const std::string& option, const std::string& path);

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
                         const std::string& png, const std::string& render);

/// The glTF options of `--compress`, `--lods` and `--textures` (the texture format serves
/// the .pov files' images too, ktx2 as jpeg). Call it before any work: with ktx2 it finds basisu.
/// @throws UsageError as require_basisu, and for `texture_fallback` without ktx2
GltfSceneOptions export_options(const std::string& compress, int lods, const std::string& textures,
                                bool texture_fallback = false);

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
                      const GltfSceneOptions& gltf);

}  // namespace cutaway::cli
