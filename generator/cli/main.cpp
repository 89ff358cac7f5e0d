// The `cutaway` command line: parses arguments and calls the libraries; nothing else lives
// here (doc/architecture.md, Style). Exit codes: 0 success, 2 bad input, 1 internal failure.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/timer.h"
#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "export/gltf_export.h"
#include "export/ply_export.h"
#include "io/batch_parser.h"
#include "io/plane_spec.h"
#include "io/scene_parser.h"
#include "io/template_parser.h"
#include "io/text_rules.h"
#include "io/yaml_reader.h"
#include "model/model_builder.h"
#include "render/diffusion_backends.h"
#include "render/image/contact_sheet.h"
#include "render/image/image.h"
#include "render/model_preview.h"
#include "render/section_preview.h"
#include "section/cross_section.h"
#include "variation/grains.h"
#include "variation/variant_batch.h"
#include "variation/variation.h"

namespace {

using Clock = std::chrono::steady_clock;

using cutaway::seconds_since;
using cutaway::cli::require_extension;
using cutaway::cli::UsageError;

/// --seed's rule (parse_seed), checked on the text before CLI11 converts it, which would
/// saturate a seed beyond 2^63 - 1 silently.
const CLI::Validator kSeedRule(
    [](std::string& text) {
      const cutaway::Outcome<uint64_t> seed = cutaway::parse_seed(text);
      return seed ? std::string() : seed.reason();
    },
    "SEED");

/// --shard's rule (parse_shard), so that an empty value is refused rather than read as "not
/// given" (which would build the whole batch).
const CLI::Validator kShardRule(
    [](std::string& text) {
      const cutaway::Outcome<cutaway::Shard> shard = cutaway::parse_shard(text);
      return shard ? std::string() : shard.reason();
    },
    "K/M");

/// The --sampling value (checked by CLI11 to be "dense" or "adaptive").
cutaway::CapSampling parse_sampling(const std::string& sampling) {
  return sampling == "adaptive" ? cutaway::CapSampling::Adaptive : cutaway::CapSampling::Dense;
}

/// Prints `--stats`: the subcommand's `stats` (empty for those without counts of their own) and
/// "outputs_fnv1a64", each file in `written` (paths relative to the working directory) with
/// the FNV-1a 64-bit hash of its bytes as 16 hex digits: what a golden test compares across
/// machines. One line of JSON on stderr.
void print_stats_line(nlohmann::ordered_json stats,
                      const std::vector<std::filesystem::path>& written) {
  nlohmann::ordered_json files = nlohmann::ordered_json::object();
  const std::filesystem::path here = std::filesystem::current_path();
  for (const std::filesystem::path& f : written) {
    files[f.lexically_proximate(here).string()] =
        cutaway::hex64(cutaway::fnv1a64(cutaway::read_file_bytes(f)));
  }
  stats["outputs_fnv1a64"] = std::move(files);
  std::fprintf(stderr, "%s\n", stats.dump().c_str());
}

/// Refuses an output option given an empty path (`-o ""`), which would otherwise read as
/// "not given" (and, for `model`, write NAME.glb).
/// @throws cutaway::OutputPathError "OPTION: the path is empty"
void refuse_empty_output_paths(const CLI::App& command) {
  for (const char* name : {"-o", "--png", "--render"}) {
    const CLI::Option* option = command.get_option_no_throw(name);
    if (option == nullptr) continue;
    for (const std::string& value : option->results())
      if (value.empty()) throw cutaway::OutputPathError(std::string(name) + ": the path is empty");
  }
}

/// `--compress none|quantize|meshopt`, `--lods N` and `--textures jpeg|png` of the commands
/// that write glTF and POV-Ray scenes.
void add_export_options(CLI::App* command, std::string& compress, int& lods,
                        std::string& textures) {
  command
      ->add_option("--compress", compress,
                   "glTF vertex data: quantize (KHR_mesh_quantization, the default; three.js, "
                   "Blender 3.4+), meshopt (quantize + EXT_meshopt_compression; three.js with "
                   "MeshoptDecoder) or none (float32)")
      ->check(CLI::IsMember({"none", "quantize", "meshopt"}));
  command
      ->add_option("--lods", lods,
                   "glTF levels of detail per mesh (MSFT_lod, nodes NAME_LOD1...): level L has "
                   "about 2^-L of the triangles, outlines and seams kept (default 0)")
      ->check(CLI::Range(0, 4));
  command
      ->add_option("--textures", textures,
                   "base-colour texture images in .glb, .gltf and .pov: jpeg (the default, about "
                   "a tenth of png's bytes) or png (lossless); material maps are always png")
      ->check(CLI::IsMember({"jpeg", "png"}));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cutaway: cut objects with a consistent interior, from diffusion surfaces "
               "(Takayama et al. 2010)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cutaway " CUTAWAY_VERSION);
  app.fallthrough();  // common options may follow the subcommand
  bool stats = false, quiet = false, verbose = false;
  app.add_flag("--stats", stats, "print JSON counts, timings and output file hashes on stderr");
  app.add_flag("-q,--quiet", quiet, "print errors only");
  app.add_flag("-v,--verbose", verbose, "print progress and details");
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (0: all cores); results do not depend on it")
      ->check(CLI::Range(0, 1024));
  std::string backend = "auto";
  app.add_option("--backend", backend,
                 "colour diffusion: cpu (Embree ray casting), gl (the same rays in an OpenGL "
                 "compute shader), auto (gl on a GPU, else cpu)")
      ->check(CLI::IsMember({"auto", "cpu", "gl"}));
  std::string sampling = "adaptive";  // dense: every vertex, for comparison
  app.add_option("--sampling", sampling,
                 "which points of a cut face are diffused: dense (every vertex) or adaptive "
                 "(sparse samples along blur bands and in the interior, interpolated and "
                 "refined where a test point disagrees)")
      ->check(CLI::IsMember({"dense", "adaptive"}));
  std::string directions = "adaptive";  // every: every cube texel, for comparison
  app.add_option("--directions", directions,
                 "which PMVC rays a point casts: adaptive (its cube at half resolution, again at "
                 "full resolution where neighbouring rays see different sheets) or every (every "
                 "texel of the cube)")
      ->check(CLI::IsMember({"adaptive", "every"}));

  cutaway::cli::ModelArgs model_args;
  CLI::App* model = app.add_subcommand("model", "build the DS model of a template (glb, PNG)");
  model->add_option("TEMPLATE", model_args.template_path, "template file (.yaml)")->required();
  model->add_option("-o,--output", model_args.output,
                    "glTF binary to write (.glb); default NAME.glb when no --png is given");
  model->add_option("--png", model_args.png, "PNG picture of the see-through model");
  model->add_option("--size", model_args.width, "PNG width and height in pixels")
      ->check(CLI::Range(16, 2880));
  model->add_option("--seed", model_args.seed, "build the random variant of this seed")
      ->check(kSeedRule);

  cutaway::cli::SectionArgs section_args;
  CLI::App* section = app.add_subcommand("section", "one cross-section with diffused colours");
  section->add_option("TEMPLATE", section_args.template_path, "template file (.yaml)")->required();
  section->add_option("--plane", section_args.plane,
                      "cutting plane: AXIS=VALUE (e.g. y=20) or px,py,pz/nx,ny,nz, template units")
      ->required();
  section->add_option("-o,--output", section_args.output,
                      "cut face to write: .glb (linear COLOR_0) or .ply (sRGB colours); "
                      "default NAME-section.glb when no --png is given");
  section->add_option("--png", section_args.png, "PNG of the cut face seen head-on (sRGB)");
  section->add_option("--size", section_args.width, "PNG width in pixels")
      ->check(CLI::Range(16, 2880));
  section->add_option("--cube", section_args.cube, "cube-map texels per face edge for PMVC")
      ->check(CLI::Range(2, 256));
  section->add_option("--seed", section_args.seed, "cut the random variant of this seed")
      ->check(kSeedRule);

  cutaway::cli::VariantsArgs variants_args;
  CLI::App* variants = app.add_subcommand(
      "variants", "random variants of a template (glb + manifest.json + contact-sheet.png)");
  variants->add_option("TEMPLATE", variants_args.template_path, "template file (.yaml)")->required();
  variants->add_option("--count", variants_args.count, "number of variants")
      ->check(CLI::Range(1, 100000));
  variants->add_option("--seed", variants_args.seed, "seed of the first variant (then seed + 1, ...)")
      ->check(kSeedRule);
  variants->add_option("-o,--output", variants_args.output_dir, "output folder")->required();
  variants->add_option("--shard", variants_args.shard,
                       "K/M: write only the K-th of M contiguous shares of the variants (seeds "
                       "unchanged, so the shards together make one unsharded run)")
      ->check(kShardRule);
  variants->add_option("--sheet", variants_args.sheet,
                       "contact-sheet.png: the mid-height horizontal cuts of the first N "
                       "variants (of the shard) at one scale; 0: none")
      ->check(CLI::Range(0, 256));
  variants->add_option("--tile", variants_args.tile,
                       "contact-sheet tile size in pixels (the largest cut's extent)")
      ->check(CLI::Range(16, 4096));

  cutaway::cli::PieceArgs piece_args;
  CLI::App* piece = app.add_subcommand(
      "piece", "cut one object into pieces with diffused cut faces (glb/gltf/pov, PNG)");
  piece->add_option("TEMPLATE", piece_args.template_path, "template file (.yaml)")->required();
  piece->add_option("--cut", piece_args.cut,
                    "halves, slices:THICKNESS, wedges:COUNT, dice:SIZE, plane:SPEC or whole "
                    "(template units)")
      ->required();
  piece->add_option("--seed", piece_args.seed, "cut the random variant of this seed")
      ->check(kSeedRule);
  piece->add_option("-o,--output", piece_args.output, "pieces to write: .glb, .gltf or .pov");
  piece->add_option("--png", piece_args.png, "PNG of the pieces pulled slightly apart");
  piece->add_option("--cube", piece_args.cube, "cube-map texels per face edge for PMVC")
      ->check(CLI::Range(2, 256));
  piece->add_option("--perlin", piece_args.perlin,
                    "Perlin colour modulation strength (0: off; default 1)")
      ->check(CLI::Range(0.0, 10.0));
  piece->add_option("--silhouettes", piece_args.silhouettes,
                    "silhouette stroke strength over the PNG and in .pov (0: off; default 1)")
      ->check(CLI::Range(0.0, 10.0));
  add_export_options(piece, piece_args.compress, piece_args.lods, piece_args.textures);
  piece->add_flag("--camera-and-lights", piece_args.camera_and_lights,
                  "write the preview's camera and studio lights into the glTF file (an asset "
                  "leaves them out by default: it goes into someone else's scene)");
  piece->add_option("--collision", piece_args.collision,
                    "convex collision hulls of each piece in the glTF file, named for godot "
                    "(NAME_collisionK-convcolonly, the default), unreal (UCX_MESH_KK) or none")
      ->check(CLI::IsMember({"none", "godot", "unreal"}));

  cutaway::cli::SheetArgs sheet_args;
  CLI::App* sheet = app.add_subcommand(
      "sheet", "contact sheet of cut templates, one labelled tile each (PNG)");
  sheet->add_option("TEMPLATE", sheet_args.items,
                    "template files, each optionally with its own cut and view: "
                    "PATH.yaml[:CUT][@up|@upright]")
      ->required();
  sheet->add_option("-o,--output", sheet_args.output, "sheet to write (.png)")->required();
  sheet->add_option("--cut", sheet_args.cut,
                    "cut of templates without their own: as piece --cut, or across (one "
                    "horizontal plane at mid-height)");
  sheet->add_option("--tile", sheet_args.tile, "tile width in pixels")
      ->check(CLI::Range(64, 2048));
  sheet->add_option("--columns", sheet_args.columns, "columns (0: about sqrt(4/3 tiles))")
      ->check(CLI::Range(0, 64));
  sheet->add_option("--cube", sheet_args.cube, "cube-map texels per face edge for PMVC")
      ->check(CLI::Range(2, 256));
  sheet->add_option("--silhouettes", sheet_args.silhouettes,
                    "silhouette stroke strength (0: off; default 1)")
      ->check(CLI::Range(0.0, 10.0));

  cutaway::cli::SceneArgs scene_args;
  CLI::App* scene = app.add_subcommand(
      "scene", "the main job: a scene of cut objects as glTF or POV-Ray, and pictures of it");
  scene->add_option("SCENE", scene_args.scene_path, "scene file (.yaml)")->required();
  scene->add_option("--seed", scene_args.seed, "seed (default: the scene file's)")
      ->check(kSeedRule);
  scene->add_option("-o,--output", scene_args.outputs,
                    "scene to write: .glb, .gltf or .pov; repeat for several formats")
      ->required()
      ->allow_extra_args(false);
  scene->add_option("--png", scene_args.png, "OpenGL preview (PNG)");
  scene->add_option("--render", scene_args.render, "POV-Ray render (PNG)");
  scene->add_option("--cube", scene_args.cube, "cube-map texels per face edge for PMVC")
      ->check(CLI::Range(2, 256));
  scene
      ->add_option("--colours", scene_args.colours,
                   "cut faces in glTF: texture (a baked texture per object, the default) or "
                   "vertex (vertex colours)")
      ->check(CLI::IsMember({"texture", "vertex"}));
  scene
      ->add_option("--texels-per-mm", scene_args.texels_per_mm,
                   "texel density of baked cut-face textures (default: the scene's "
                   "render.texels_per_mm, else 8.6: a 60 mm cut face 516 texels across)")
      ->check(CLI::Range(0.1, 100.0));
  scene->add_flag("--power-of-two", scene_args.power_of_two,
                  "baked textures with sides powers of two (default: multiples of 4, fewer "
                  "texels)");
  add_export_options(scene, scene_args.compress, scene_args.lods, scene_args.textures);

  cutaway::cli::BatchArgs batch_args;
  CLI::App* batch = app.add_subcommand(
      "batch", "asset batches: solid cut pieces per variant and cut, sharded, resumable, on "
               "Slurm (doc/batch-format.md)");
  batch->require_subcommand(0, 1);
  batch->add_option("BATCH", batch_args.batch_path, "batch file (.yaml)");
  batch->add_option("-o,--output", batch_args.output_dir, "output folder");
  batch->add_option("--shard", batch_args.shard,
                    "K/M: build only the K-th of M contiguous shares of the variants")
      ->check(kShardRule);
  batch->add_flag("--slurm", batch_args.slurm,
                  "write DIR/batch.sbatch, an sbatch array job of --array shards, and submit it");
  batch->add_option("--array", batch_args.array, "with --slurm: array tasks (shards; default 4)")
      ->check(CLI::Range(1, 100000));
  batch->add_option("--partition", batch_args.partition, "with --slurm: the Slurm partition");
  batch->add_option("--time", batch_args.time, "with --slurm: each task's time limit (e.g. 2:00:00)");
  batch->add_option("--cpus-per-task", batch_args.cpus_per_task,
                    "with --slurm: CPUs per task, its --threads (default 1)")
      ->check(CLI::Range(1, 1024));
  batch->add_flag("--dry-run", batch_args.dry_run, "with --slurm: write the script, do not submit");
  std::string merge_dir;
  CLI::App* batch_merge = batch->add_subcommand(
      "merge", "check and merge the shards' manifests of DIR; write manifest.jsonl and "
               "contact-sheet.png");
  batch_merge->add_option("DIR", merge_dir, "the batch's output folder")->required();

  std::vector<std::string> check_files;
  CLI::App* check =
      app.add_subcommand("check", "validate templates, scenes and batches without writing anything");
  check->add_option("FILE", check_files, "template, scene and batch files")->required();

  cutaway::cli::EditArgs edit_args;
  CLI::App* edit = app.add_subcommand(
      "edit", "the template editor in the browser: a local server on 127.0.0.1 (doc/editor.md)");
  edit->add_option("TEMPLATE", edit_args.template_path,
                   "template file (.yaml); may be new (default new-template.yaml here)");
  edit->add_option("--port", edit_args.port, "port on 127.0.0.1 (default 8765; 0: any free port, printed)")
      ->check(CLI::Range(0, 65535));

  auto logger = spdlog::stderr_color_st("cutaway");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("%v");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  spdlog::set_level(quiet ? spdlog::level::err
                          : (verbose ? spdlog::level::debug : spdlog::level::info));
  // Every file a command writes goes through `outputs`: registered and checked before any
  // work, committed (renamed into place together) only when the command succeeds.
  cutaway::OutputSet outputs;
  nlohmann::ordered_json stats_json = nlohmann::ordered_json::object();
  const auto run = [&]() -> int {
    for (const CLI::App* command : app.get_subcommands()) refuse_empty_output_paths(*command);
    const cutaway::cli::Common common{backend, threads, stats ? &stats_json : nullptr,
                                      parse_sampling(sampling),
                                      directions == "adaptive"};
    if (*model) {
      if (!model_args.output.empty()) require_extension("-o", model_args.output, ".glb");
      if (!model_args.png.empty()) require_extension("--png", model_args.png, ".png");
      return cutaway::cli::run_model(model_args, common, outputs);
    }
    if (*section) {
      if (!section_args.output.empty() &&
          std::filesystem::path(section_args.output).extension() != ".ply") {
        require_extension("-o", section_args.output, ".glb");
      }
      if (!section_args.png.empty()) require_extension("--png", section_args.png, ".png");
      return cutaway::cli::run_section(section_args, common, outputs);
    }
    if (*check) return cutaway::cli::run_check(check_files);
    if (*edit) return cutaway::cli::run_edit(edit_args);
    if (*piece) return cutaway::cli::run_piece(piece_args, common, outputs);
    if (*sheet) return cutaway::cli::run_sheet(sheet_args, common, outputs);
    if (*scene) return cutaway::cli::run_scene(scene_args, common, outputs);
    if (*batch_merge) return cutaway::cli::run_batch_merge(merge_dir);
    if (*batch) return cutaway::cli::run_batch_command(batch_args, common, quiet);
    if (*variants) {
      variants_args.shard_given = variants->count("--shard") > 0;
      return cutaway::cli::run_variants(variants_args, common, quiet, outputs);
    }
    return 0;
  };
  try {
    const int code = run();
    if (code == 0) {
      outputs.commit();
      if (stats) print_stats_line(stats_json, outputs.committed());
    }
    return code;
  } catch (const cutaway::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "cutaway: %s\n", e.what());
    return 2;
  } catch (const cutaway::OutputPathError& e) {
    std::fprintf(stderr, "cutaway: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    // A writer's error names its staging path; describe() names the user's file instead.
    std::fprintf(stderr, "cutaway: error: %s\n", outputs.describe(e.what()).c_str());
    return 1;
  }
}
