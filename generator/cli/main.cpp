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
using cutaway::cli::print_stats;
using cutaway::cli::require_extension;
using cutaway::cli::UsageError;

struct ModelArgs {
  std::string template_path;
  std::string output;
  std::string png;
  int width = 800;
  int64_t seed = -1;  ///< >= 0: build the variant of this seed instead of the template
};

int run_model(const ModelArgs& a, bool stats, cutaway::OutputSet& outputs) {
  const auto t0 = Clock::now();
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  const std::string glb = a.output.empty() && a.png.empty() ? tmpl.name + ".glb" : a.output;
  const std::filesystem::path glb_file = glb.empty() ? "" : outputs.add("-o", glb);
  const std::filesystem::path png_file = a.png.empty() ? "" : outputs.add("--png", a.png);
  const double t_parse = seconds_since(t0);
  const auto t1 = Clock::now();
  const cutaway::DsModel model =
      a.seed >= 0 ? cutaway::make_variant(tmpl, static_cast<uint64_t>(a.seed)).model
                  : cutaway::build_model(tmpl);
  const double t_sweep = seconds_since(t1);
  spdlog::info("{}: {} surfaces, {} vertices, {} faces", tmpl.name, model.surfaces.size(),
               model.vertex_count(), model.face_count());

  double t_render = 0, t_export = 0;
  cutaway::Image image;
  if (!a.png.empty()) {
    const auto t2 = Clock::now();
    cutaway::PreviewOptions opt;
    opt.width = opt.height = a.width;
    image = cutaway::render_model_preview(model, opt);
    t_render = seconds_since(t2);
  }
  if (!glb.empty()) {
    const auto t3 = Clock::now();
    cutaway::write_model_glb(glb_file, model, cutaway::GltfModelOptions{});
    t_export = seconds_since(t3);
    spdlog::info("wrote {}", glb);
  }
  if (!a.png.empty()) {
    cutaway::write_png(png_file, image);
    spdlog::info("wrote {}", a.png);
  }
  if (stats) {
    print_stats({{"template", tmpl.name},
                 {"surfaces", model.surfaces.size()},
                 {"vertices", model.vertex_count()},
                 {"faces", model.face_count()},
                 {"seconds",
                  {{"parse", t_parse}, {"sweep", t_sweep}, {"render", t_render},
                   {"export", t_export}}}});
  }
  return 0;
}

struct SectionArgs {
  std::string template_path;
  std::string plane;
  std::string output;
  std::string png;
  int cube = 16;
  int width = 800;
  int64_t seed = -1;  ///< >= 0: cut the variant of this seed instead of the template
};

/// The --sampling value (checked by CLI11 to be "dense" or "adaptive").
cutaway::CapSampling parse_sampling(const std::string& sampling) {
  return sampling == "adaptive" ? cutaway::CapSampling::Adaptive : cutaway::CapSampling::Dense;
}

int run_section(const SectionArgs& a, const std::string& backend, int threads, bool stats,
                cutaway::CapSampling sampling, cutaway::OutputSet& outputs) {
  const auto t0 = Clock::now();
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  cutaway::Plane plane;
  try {
    plane = cutaway::parse_plane_spec(a.plane, tmpl.metres_per_unit);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--plane: ") + e.what());
  }
  const std::string out = a.output.empty() && a.png.empty() ? tmpl.name + "-section.glb" : a.output;
  const std::filesystem::path out_file = out.empty() ? "" : outputs.add("-o", out);
  const std::filesystem::path png_file = a.png.empty() ? "" : outputs.add("--png", a.png);
  const cutaway::DsModel model =
      a.seed >= 0 ? cutaway::make_variant(tmpl, static_cast<uint64_t>(a.seed)).model
                  : cutaway::build_model(tmpl);
  const double t_model = seconds_since(t0);
  const auto t1 = Clock::now();
  const auto diffusion = cutaway::make_diffusion(model, {a.cube, threads},
                                                 cutaway::parse_diffusion_choice(backend));
  const double t_backend = seconds_since(t1);
  const auto t2 = Clock::now();
  cutaway::CrossSectionOptions options{tmpl.edge_m};
  options.sampling = sampling;
  cutaway::Outcome<cutaway::CrossSection> made =
      cutaway::make_cross_section(model, plane, *diffusion, options);
  if (!made) throw UsageError("--plane " + cutaway::quoted(a.plane) + ": " + made.reason());
  const cutaway::CrossSection section = std::move(*made);
  const double t_section = seconds_since(t2);
  spdlog::info("{}: cross-section with {} vertices ({} interior), {} triangles", tmpl.name,
               section.position.size(), section.interior_vertices, section.triangle.size());
  cutaway::Image image;
  if (!a.png.empty()) {
    cutaway::SectionPreviewOptions opt;
    opt.width = a.width;
    image = cutaway::render_section_preview(section, opt);
  }
  if (!out.empty()) {
    const bool ply = std::filesystem::path(out).extension() == ".ply";
    cutaway::write_file_atomically(
        out_file, ply ? cutaway::section_to_ply(section) : cutaway::section_to_glb(section));
    spdlog::info("wrote {}", out);
  }
  if (!a.png.empty()) {
    cutaway::write_png(png_file, image);
    spdlog::info("wrote {}", a.png);
  }
  if (stats) {
    print_stats({{"template", tmpl.name},
                 {"backend", diffusion->name()},
                 {"ds_faces", model.face_count()},
                 {"cut_segments", section.cut_segments},
                 {"vertices", section.position.size()},
                 {"interior_vertices", section.interior_vertices},
                 {"diffused_points", section.diffused_points},
                 {"rays", section.diffused_points * 6 * static_cast<size_t>(a.cube * a.cube)},
                 {"seconds",
                  {{"model", t_model},
                   {"backend_setup", t_backend},
                   {"section", t_section},
                   {"triangulate", section.seconds_triangulate},
                   {"diffuse", section.seconds_diffuse}}}});
  }
  return 0;
}

/// Builds the model of each template in `paths` once, so that its geometric rules are checked
/// too (a scene's or batch's templates).
void check_models(const std::vector<std::string>& paths) {
  for (const std::string& path : std::set<std::string>(paths.begin(), paths.end())) {
    const cutaway::Template t = cutaway::load_template(path);
    cutaway::check_grain_limits(t, cutaway::build_model(t));
  }
}

int run_check(const std::vector<std::string>& files) {
  int failed = 0;
  for (const auto& f : files) {
    try {
      // A scene or batch says so in its `format` (cutaway-scene/..., cutaway-batch/...);
      // anything else is a template.
      const auto format = cutaway::load_yaml_file(f).get("format");
      const std::string kind = format && format->is_scalar() ? format->string() : "";
      if (kind.rfind("cutaway-batch/", 0) == 0) {
        const cutaway::Batch batch = cutaway::load_batch(f);
        int variants = 0, assets = 0;
        std::vector<std::string> templates;
        for (const auto& item : batch.items) {
          variants += item.count;
          assets += item.count * static_cast<int>(item.cuts.size());
          templates.push_back(item.template_path);
        }
        check_models(templates);
        std::printf("%s: ok (batch '%s', %zu items, %d variants, %d assets)\n", f.c_str(),
                    batch.name.c_str(), batch.items.size(), variants, assets);
        continue;
      }
      if (kind.rfind("cutaway-scene/", 0) == 0) {
        const cutaway::Scene scene = cutaway::load_scene(f);
        int objects = 0;
        std::vector<std::string> templates;
        for (const auto& item : scene.items) {
          objects += item.count;
          templates.push_back(item.template_path);
        }
        check_models(templates);
        std::printf("%s: ok (scene '%s', %zu items, %d objects)\n", f.c_str(),
                    scene.name.c_str(), scene.items.size(), objects);
        continue;
      }
      const cutaway::Template tmpl = cutaway::load_template(f);
      const cutaway::DsModel model = cutaway::build_model(tmpl);
      cutaway::check_grain_limits(tmpl, model);
      std::printf("%s: ok (template '%s', %zu surfaces, %zu DS faces)\n", f.c_str(),
                  tmpl.name.c_str(), model.surfaces.size(), model.face_count());
    } catch (const cutaway::InputError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      ++failed;
    }
  }
  return failed ? 2 : 0;
}

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

/// The horizontal cut of a variant for its contact-sheet tile: the plane y = mid-height of
/// the skin's bounding box, coloured by PMVC with 8 x 8 texels per cube face (a quarter of
/// the rays of `section`'s default 16: enough for a thumbnail); none when it misses the skin.
cutaway::Outcome<cutaway::CrossSection> variant_section(const cutaway::Variant& v,
                                                        const std::string& backend, int threads) {
  const cutaway::DsMesh& skin = v.model.skin().mesh;
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (const auto vh : skin.vertices()) {
    lo = std::min(lo, skin.point(vh)[1]);
    hi = std::max(hi, skin.point(vh)[1]);
  }
  cutaway::Plane plane;
  plane.point = {0, 0.5 * (lo + hi), 0};
  plane.normal = {0, 1, 0};
  const auto diffusion = cutaway::make_diffusion(v.model, {8, threads},
                                                 cutaway::parse_diffusion_choice(backend));
  return cutaway::make_cross_section(v.model, plane, *diffusion, {v.tmpl.edge_m});
}

int run_variants(const VariantsArgs& a, const std::string& backend, int threads, bool quiet,
                 cutaway::OutputSet& outputs) {
  cutaway::Shard shard;
  if (a.shard_given) {
    const cutaway::Outcome<cutaway::Shard> parsed = cutaway::parse_shard(a.shard);
    if (!parsed) throw UsageError("--shard: " + parsed.reason());
    shard = *parsed;
  }
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  const std::filesystem::path dir(a.output_dir);
  const int first = shard.begin(a.count), last = shard.end(a.count);
  // Every file is registered (and DIR created) before the first variant is built.
  std::vector<std::filesystem::path> glb_files;
  for (int i = first; i < last; ++i) {
    const uint64_t seed = a.seed + static_cast<uint64_t>(i);
    glb_files.push_back(
        outputs.add("-o", (dir / (tmpl.name + "-" + std::to_string(seed) + ".glb")).string()));
  }
  const std::filesystem::path manifest_file = outputs.add("-o", (dir / "manifest.json").string());
  const std::filesystem::path sheet_file =
      a.sheet > 0 ? outputs.add("-o", (dir / "contact-sheet.png").string())
                  : std::filesystem::path();
  std::vector<cutaway::VariantRecord> records;
  const cutaway::cli::ProgressBar progress("variants", last - first, !quiet && isatty(fileno(stderr)));
  progress.show(0);
  std::vector<cutaway::CrossSection> sections;
  std::vector<int> missing;  // sheet tiles whose plane gave no section
  for (int i = first; i < last; ++i) {
    const uint64_t seed = a.seed + static_cast<uint64_t>(i);
    const auto t0 = Clock::now();
    const cutaway::Variant v = cutaway::make_variant(tmpl, seed);
    const std::string glb = cutaway::model_to_glb(v.model, cutaway::GltfModelOptions{});
    const std::string file = tmpl.name + "-" + std::to_string(seed) + ".glb";
    cutaway::write_file_atomically(glb_files[static_cast<size_t>(i - first)], glb);
    records.push_back({file, seed, cutaway::fnv1a64(glb), v.model.face_count(), v.tmpl.folds});
    spdlog::debug("wrote {} ({:.2f} s)", (dir / file).string(), seconds_since(t0));
    progress.show(i - first + 1);
  }
  cutaway::write_file_atomically(
      manifest_file, cutaway::variant_manifest(
                         tmpl.name, a.shard_given ? std::optional(shard) : std::nullopt, records));
  // The contact sheet comes last (all files are committed together, or none); its variants
  // are built again (same seed, same model) rather than all kept.
  for (int i = first; i < std::min(last, first + a.sheet); ++i) {
    const uint64_t seed = a.seed + static_cast<uint64_t>(i);
    cutaway::Outcome<cutaway::CrossSection> section =
        variant_section(cutaway::make_variant(tmpl, seed), backend, threads);
    if (section) {
      sections.push_back(std::move(*section));
    } else {
      spdlog::warn("seed {}: no horizontal section at mid-height ({}); its tile stays empty",
                   seed, section.reason());
      missing.push_back(i - first);
    }
  }
  if (!sections.empty()) {
    cutaway::SectionTileOptions tile_options;
    tile_options.tile_px = a.tile;
    std::vector<cutaway::Image> tiles = cutaway::render_section_tiles(sections, tile_options);
    for (int m : missing) {  // an empty tile of the same size where a section is missing
      cutaway::Image blank = tiles.front();
      std::fill(blank.rgba.begin(), blank.rgba.end(), uint8_t{255});
      tiles.insert(tiles.begin() + m, std::move(blank));
    }
    const int columns =
        static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles.size()))));
    cutaway::write_png(sheet_file, cutaway::compose_grid(tiles, columns));
  }
  spdlog::info("wrote {} variant(s) of {}, manifest.json{} to {}", last - first, tmpl.name,
               sections.empty() ? "" : ", contact-sheet.png", dir.string());
  return 0;
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
  app.add_flag("--stats", stats, "print JSON timings and counts on stderr");
  app.add_flag("-q,--quiet", quiet, "print errors only");
  app.add_flag("-v,--verbose", verbose, "print progress and details");
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (0: all cores); results do not depend on it")
      ->check(CLI::Range(0, 1024));
  std::string backend = "auto";
  app.add_option("--backend", backend,
                 "colour diffusion: cpu (Embree), gl (OpenGL cube maps), auto (gl on a GPU, "
                 "else cpu)")
      ->check(CLI::IsMember({"auto", "cpu", "gl"}));
  std::string sampling = "adaptive";  // dense: every vertex, for comparison
  app.add_option("--sampling", sampling,
                 "which points of a cut face are diffused: dense (every vertex) or adaptive "
                 "(sparse samples along blur bands and in the interior, interpolated and "
                 "refined where a test point disagrees)")
      ->check(CLI::IsMember({"dense", "adaptive"}));

  ModelArgs model_args;
  CLI::App* model = app.add_subcommand("model", "build the DS model of a template (glb, PNG)");
  model->add_option("TEMPLATE", model_args.template_path, "template file (.yaml)")->required();
  model->add_option("-o,--output", model_args.output,
                    "glTF binary to write (.glb); default NAME.glb when no --png is given");
  model->add_option("--png", model_args.png, "PNG picture of the see-through model");
  model->add_option("--size", model_args.width, "PNG width and height in pixels")
      ->check(CLI::Range(16, 8192));
  model->add_option("--seed", model_args.seed, "build the random variant of this seed")
      ->check(CLI::NonNegativeNumber);

  SectionArgs section_args;
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
      ->check(CLI::Range(16, 8192));
  section->add_option("--cube", section_args.cube, "cube-map texels per face edge for PMVC")
      ->check(CLI::Range(2, 256));
  section->add_option("--seed", section_args.seed, "cut the random variant of this seed")
      ->check(CLI::NonNegativeNumber);

  VariantsArgs variants_args;
  CLI::App* variants = app.add_subcommand(
      "variants", "random variants of a template (glb + manifest.json + contact-sheet.png)");
  variants->add_option("TEMPLATE", variants_args.template_path, "template file (.yaml)")->required();
  variants->add_option("--count", variants_args.count, "number of variants")
      ->check(CLI::Range(1, 100000));
  variants->add_option("--seed", variants_args.seed, "seed of the first variant (then seed + 1, ...)");
  variants->add_option("-o,--output", variants_args.output_dir, "output folder")->required();
  variants->add_option("--shard", variants_args.shard,
                       "K/M: write only the K-th of M contiguous shares of the variants (seeds "
                       "unchanged, so the shards together make one unsharded run)");
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
      ->check(CLI::NonNegativeNumber);
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
      ->check(CLI::NonNegativeNumber);
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
  add_export_options(scene, scene_args.compress, scene_args.lods, scene_args.textures);

  cutaway::cli::BatchArgs batch_args;
  CLI::App* batch = app.add_subcommand(
      "batch", "asset batches: solid cut pieces per variant and cut, sharded, resumable, on "
               "Slurm (doc/batch-format.md)");
  batch->require_subcommand(0, 1);
  batch->add_option("BATCH", batch_args.batch_path, "batch file (.yaml)");
  batch->add_option("-o,--output", batch_args.output_dir, "output folder");
  batch->add_option("--shard", batch_args.shard,
                    "K/M: build only the K-th of M contiguous shares of the variants");
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
  const auto run = [&]() -> int {
    for (const CLI::App* command : app.get_subcommands()) refuse_empty_output_paths(*command);
    if (*model) {
      if (!model_args.output.empty()) require_extension("-o", model_args.output, ".glb");
      if (!model_args.png.empty()) require_extension("--png", model_args.png, ".png");
      return run_model(model_args, stats, outputs);
    }
    if (*section) {
      if (!section_args.output.empty() &&
          std::filesystem::path(section_args.output).extension() != ".ply") {
        require_extension("-o", section_args.output, ".glb");
      }
      if (!section_args.png.empty()) require_extension("--png", section_args.png, ".png");
      return run_section(section_args, backend, threads, stats, parse_sampling(sampling), outputs);
    }
    if (*check) return run_check(check_files);
    const cutaway::cli::Common common{backend, threads, stats, parse_sampling(sampling)};
    if (*piece) return cutaway::cli::run_piece(piece_args, common, outputs);
    if (*sheet) return cutaway::cli::run_sheet(sheet_args, common, outputs);
    if (*scene) return cutaway::cli::run_scene(scene_args, common, outputs);
    if (*batch_merge) return cutaway::cli::run_batch_merge(merge_dir);
    if (*batch) return cutaway::cli::run_batch_command(batch_args, common, quiet);
    if (*variants) {
      variants_args.shard_given = variants->count("--shard") > 0;
      return run_variants(variants_args, backend, threads, quiet, outputs);
    }
    return 0;
  };
  try {
    const int code = run();
    if (code == 0) outputs.commit();
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
