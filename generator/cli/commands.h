// The `cutaway` subcommands, one source file each (NAME_command.cpp), and what they share;
// main.cpp parses the arguments and calls them.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "model/ds_model.h"
#include "model/template.h"
#include "pieces/cut_spec.h"
#include "pieces/pieces.h"
#include "scene/object_cut.h"
#include "variation/variation.h"

namespace cutaway::cli {

/// A bad command-line argument: reported like InputError, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws UsageError unless `path` ends in `ext` (e.g. ".glb").
inline void require_extension(const std::string& option, const std::string& path,
                              const char* ext) {
  if (std::filesystem::path(path).extension() != ext) {
    throw UsageError(option + ": '" + path + "' must end in " + ext);
  }
}

// Outputs: every subcommand registers each file it will write in the OutputSet main() owns,
// before any work, writes to the path add() returns, and main() commits the set when the
// subcommand returns 0 (atomic_file.h; a refused path is OutputPathError, exit code 2).

/// Options common to all subcommands.
struct Common {
  std::string backend = "auto";  ///< auto | cpu | gl
  int threads = 0;               ///< 0: all cores
  /// `--stats`: where a subcommand puts its JSON counts and "seconds" per stage (keys in the
  /// order given); null without --stats. main() prints it as one line on stderr once the
  /// outputs are committed, with "outputs_fnv1a64" added (each written file's content hash).
  nlohmann::ordered_json* stats = nullptr;
  CapSampling sampling = CapSampling::Adaptive;  ///< --sampling: which cap points are diffused
  bool adaptive_directions = true;  ///< --directions adaptive (true) or every (false)
};

/// `text` (the `--cut` notation) for `tmpl`, refused when it is malformed or would make more
/// than kMaxPiecesPerCut pieces.
/// @throws UsageError "WHAT: rule" (`what` names the cut for the user)
CutSpec checked_cut(const Template& tmpl, const std::string& text, const std::string& what);

/// The diffusion backend --backend chooses, with cube-map size `cube`, --threads and
/// --directions.
DiffusionFactory diffusion_factory(int cube, const Common& common);

/// `variant` cut for a picture of its pieces (`piece`, `sheet`): every piece kept, vertex
/// colours modulated by the template's Perlin bands with strength `perlin` and `seed` in the
/// object frame, the template's materials added to `assets`, the backend --backend chooses
/// with cube-map size `cube` (cut_object).
/// @throws UsageError "WHAT: rule" when the cut misses the object (`what` names the cut)
CutObject cut_for_view(SceneAssets& assets, const Variant& variant, const CutSpec& cut, int cube,
                       const Common& common, double perlin, uint64_t seed,
                       const std::string& what);

/// `cutaway model TEMPLATE [-o model.glb] [--png view.png] [--size PX] [--seed S]`
/// (generator/cli/model_command.cpp).
struct ModelArgs {
  std::string template_path;
  std::string output;
  std::string png;
  int width = 800;
  int64_t seed = -1;  ///< >= 0: build the variant of this seed instead of the template
};
int run_model(const ModelArgs& args, const Common& common, OutputSet& outputs);

/// `cutaway section TEMPLATE --plane SPEC [-o cut.glb|cut.ply] [--png cut.png] [--cube N]
/// [--seed S]` (generator/cli/section_command.cpp).
struct SectionArgs {
  std::string template_path;
  std::string plane;
  std::string output;
  std::string png;
  int cube = 16;
  int width = 800;
  int64_t seed = -1;  ///< >= 0: cut the variant of this seed instead of the template
};
int run_section(const SectionArgs& args, const Common& common, OutputSet& outputs);

/// `cutaway variants TEMPLATE --count N [--seed S] -o DIR [--shard K/M] [--sheet N] [--tile PX]`
/// (generator/cli/variants_command.cpp).
struct VariantsArgs {
  std::string template_path;
  std::string output_dir;
  int count = 1;
  uint64_t seed = 0;
  std::string shard;  ///< "K/M" when shard_given
  bool shard_given = false;
  int sheet = 64;     ///< contact sheet: at most this many tiles (0: no sheet)
  int tile = 256;     ///< contact-sheet tile size, pixels
};
int run_variants(const VariantsArgs& args, const Common& common, bool quiet, OutputSet& outputs);

/// `cutaway check FILE...`: each template, scene or batch file read and checked (its templates'
/// models built), "FILE: ok (...)" on stdout or the error on stderr; 2 when any failed
/// (generator/cli/check_command.cpp).
int run_check(const std::vector<std::string>& files);

/// `cutaway edit TEMPLATE [--port N]` (generator/cli/edit_command.cpp): serves the template
/// editor on 127.0.0.1 until interrupted. TEMPLATE need not exist yet (a new template).
struct EditArgs {
  std::string template_path = "new-template.yaml";  ///< opened, or made on the first Save
  int port = 8765;
};
int run_edit(const EditArgs& args);

/// `cutaway piece TEMPLATE --cut SPEC [--seed S] [-o pieces.glb|.gltf|.pov] [--png p.png]`.
struct PieceArgs {
  std::string template_path, cut, output, png;
  int64_t seed = -1;  ///< >= 0: cut the variant of this seed instead of the template
  int width = 800, height = 600;
  int cube = 16;
  double perlin = 1.0;  ///< Perlin colour modulation strength (the template's npr bands)
  double silhouettes = 1.0;  ///< silhouette stroke strength over the PNG and in .pov; 0: none
  std::string compress = "quantize";  ///< glTF vertex data: none, quantize or meshopt
  int lods = 0;                       ///< glTF levels of detail per mesh (GltfSceneOptions)
  std::string textures = "jpeg";      ///< base-colour texture images: jpeg or png (TextureFormat)
  bool camera_and_lights = false;     ///< --camera-and-lights: write them into the glTF
  std::string collision = "godot";    ///< --collision: none, godot or unreal hull names
};
int run_piece(const PieceArgs& args, const Common& common, OutputSet& outputs);

/// `cutaway scene SCENE [--seed S] -o OUT.glb|.gltf|.pov [-o ...] [--png preview.png]
/// [--render out.png]`: one build, any number of exports.
struct SceneArgs {
  std::string scene_path, png, render;
  std::vector<std::string> outputs;
  int64_t seed = -1;  ///< >= 0: overrides the scene's seed
  int cube = 16;
  std::string colours = "texture";  ///< "texture" or "vertex" (CapColours)
  double texels_per_mm = 0;         ///< CapAtlasOptions::texels_per_m / 1000; 0: the scene's
  bool power_of_two = false;        ///< --power-of-two: texture sides powers of two
  std::string compress = "quantize";  ///< glTF vertex data: none, quantize or meshopt
  int lods = 0;                       ///< glTF levels of detail per mesh (GltfSceneOptions)
  std::string textures = "jpeg";      ///< base-colour texture images: jpeg or png (TextureFormat)
};
int run_scene(const SceneArgs& args, const Common& common, OutputSet& outputs);

/// `cutaway sheet TEMPLATE[:CUT][@VIEW]... -o sheet.png [--cut SPEC] [--tile PX] [--columns N]`:
/// a contact sheet, one labelled tile per template, cut (by CUT or --cut: a `piece --cut` spec,
/// or `across`, one horizontal plane through the middle) with its pieces laid out cut face up
/// (VIEW up, the default) or standing with their cut faces toward the camera (VIEW upright)
/// (generator/cli/sheet_command.cpp).
struct SheetArgs {
  std::vector<std::string> items;  ///< "PATH.yaml[:CUT][@VIEW]"
  std::string output;              ///< .png
  std::string cut = "halves";      ///< the cut of items without their own
  int tile = 400;                  ///< tile width in pixels (height 3/4 of it plus the label)
  int columns = 0;                 ///< 0: about sqrt(4/3 * tiles)
  int cube = 16;
  double silhouettes = 1.0;  ///< silhouette stroke strength; 0: none
};
int run_sheet(const SheetArgs& args, const Common& common, OutputSet& outputs);

/// `cutaway batch BATCH.yaml -o DIR [--shard K/M]`, or with `--slurm [--array M] [--partition
/// P] [--time T] [--cpus-per-task C] [--dry-run]` an sbatch array script written into DIR and
/// submitted (generator/cli/batch_command.cpp; doc/batch-format.md).
struct BatchArgs {
  std::string batch_path, output_dir, shard;  ///< shard: "" for the whole batch
  bool slurm = false, dry_run = false;
  int array = 4, cpus_per_task = 1;
  std::string partition, time;
};
int run_batch_command(const BatchArgs& args, const Common& common, bool quiet);

/// The exit code of `batch merge` when shards are still missing: not bad input (2) nor a
/// failure (1), but more work due.
inline constexpr int kExitBatchIncomplete = 3;

/// `cutaway batch merge DIR`: checks the shards' manifests against batch.json, writes
/// manifest.jsonl and contact-sheet.png (the sample's thumbnails, labelled) when every asset is
/// there; returns kExitBatchIncomplete when the batch is incomplete.
int run_batch_merge(const std::string& dir);

}  // namespace cutaway::cli
