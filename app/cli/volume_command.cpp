// `cutaway volume`: a variant's interior as a volume (OpenVDB, flipbook PNGs with a JSON
// sidecar, and the whole object as glTF referring to them). Argument checks and calls into the
// libraries only.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "app/cli/scene_outputs.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/timer.h"
#include "cut/piece_views.h"
#include "diffusion/diffusion.h"
#include "export/vdb_export.h"
#include "export/volume_flipbook.h"
#include "io/template_parser.h"
#include "material/colour_modulation.h"
#include "model/model_builder.h"
#include "variation/variation.h"
#include "volume/interior_volume.h"
#include "volume/volume_cost.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

/// `cutaway volume TEMPLATE -o OUT [-o ...] [--seed S] [--voxel LENGTH] [--cube N]
/// [--perlin S]`.
struct VolumeArgs {
  std::string template_path;
  std::vector<std::string> outputs;
  int64_t seed = -1;  ///< >= 0: the variant of this seed instead of the template
  double voxel = 0;   ///< template units; 0 (not given): default_voxel_length
  int cube = kDefaultCubeSize;
  double perlin = 1.0;  ///< Perlin colour modulation strength (the template's npr bands)
};

/// The files one run writes, as the user named them ("" when not asked for).
struct VolumePaths {
  std::string vdb, sidecar, gltf;
};

/// Refuses a stem (an -o without extension) that names a folder rather than files beside
/// one: a trailing '/', ".", ".." or an existing folder ('d2/' would write 'd2/.vdb', '.' would
/// write '..vdb'); and one that is an output's extension alone ('d2/.json', which has no
/// extension to std::filesystem, would write 'd2/.json.vdb').
/// @throws UsageError "-o \"STEM\": RULE"
void require_file_stem(const std::string& stem) {
  const fs::path path(stem);
  const fs::path name = path.filename();
  std::error_code ec;
  if (name.empty() || name == "." || name == ".." || fs::is_directory(path, ec))
    throw UsageError("-o " + quoted(stem) +
                     ": a stem names the files STEM.vdb, STEM.json and "
                     "STEM.glb, not a folder; give a file name, e.g. " +
                     quoted((path / "").string() + "NAME"));
  for (const char* ext : {".vdb", ".json", ".glb", ".gltf"})
    if (name == ext)
      throw UsageError("-o " + quoted(stem) + ": no file name before the extension; give e.g. " +
                       quoted((path.parent_path() / "NAME").string() + ext));
}

/// -o paths sorted by form: a stem without extension asks for all three forms.
/// @throws UsageError for another extension, a form asked twice, a glTF with no volume, or a
///         stem that names a folder (require_file_stem)
VolumePaths volume_paths(const std::vector<std::string>& outputs) {
  VolumePaths paths;
  auto set = [](std::string& slot, const std::string& path) {
    if (!slot.empty())
      throw UsageError("-o " + quoted(path) + ": a second " + fs::path(path).extension().string() +
                       " output");
    slot = path;
  };
  for (const std::string& o : outputs) {
    const std::string ext = fs::path(o).extension().string();
    if (ext.empty()) {
      require_file_stem(o);
      set(paths.vdb, o + ".vdb");
      set(paths.sidecar, o + ".json");
      set(paths.gltf, o + ".glb");
    } else if (ext == ".vdb") {
      set(paths.vdb, o);
    } else if (ext == ".json") {
      set(paths.sidecar, o);
    } else if (ext == ".glb" || ext == ".gltf") {
      set(paths.gltf, o);
    } else {
      throw UsageError("-o " + quoted(o) +
                       ": must end in .vdb, .json (flipbooks) or .glb/.gltf, or have no "
                       "extension (all three)");
    }
  }
  if (!paths.gltf.empty() && paths.vdb.empty() && paths.sidecar.empty())
    throw UsageError("-o " + quoted(paths.gltf) +
                     ": the glTF refers to the volume in its extras; also give a .json or .vdb "
                     "output (or a stem without extension for all three)");
  return paths;
}

/// `path` relative to the folder of `from` (both as the user gave them), '/'-separated.
std::string relative_to(const std::string& path, const std::string& from) {
  const fs::path base = fs::absolute(fs::path(from)).parent_path();
  return fs::absolute(fs::path(path)).lexically_normal().lexically_relative(base).generic_string();
}

/// The flipbook PNG beside sidecar `json`: its stem + "." + channel + ".png".
std::string flipbook_path(const std::string& json, const std::string& channel) {
  fs::path p(json);
  p.replace_extension();
  return p.string() + "." + channel + ".png";
}

/// How to get a volume of `model` at cube size `cube` under the bounds (most_voxels_across):
/// "give --voxel L or longer (N voxels along the skin's longest edge), or a smaller --cube",
/// L in template units (`metres_per_unit`), rounded up to 3 significant digits.
std::string coarser_grid_advice(const DsModel& model, double metres_per_unit, int cube) {
  const auto [lo, hi] = skin_bounds(model);
  const glm::dvec3 extent = hi - lo;
  const int across = std::max(most_voxels_across(extent, cube), 1);
  const double voxel = std::max({extent.x, extent.y, extent.z}) / across / metres_per_unit;
  const double step = std::pow(10.0, std::floor(std::log10(voxel)) - 2);
  return fmt::format("give --voxel {:.3g} or longer ({} voxels along the skin's longest edge), "
                     "or a smaller --cube",
                     std::ceil(voxel / step) * step, across);
}

int run_volume(const VolumeArgs& a, const Common& common, OutputSet& outputs) {
  const VolumePaths paths = volume_paths(a.outputs);
  fs::path vdb_file, sidecar_file, colour_file, structure_file, material_file;
  if (!paths.vdb.empty()) vdb_file = outputs.add("-o", paths.vdb);
  if (!paths.sidecar.empty()) {
    sidecar_file = outputs.add("-o", paths.sidecar);
    colour_file = outputs.add("-o", flipbook_path(paths.sidecar, "colour"));
    structure_file = outputs.add("-o", flipbook_path(paths.sidecar, "structure"));
    material_file = outputs.add("-o", flipbook_path(paths.sidecar, "material"));
  }
  const Targets targets =
      paths.gltf.empty() ? Targets{} : register_outputs(outputs, {paths.gltf}, "", "");

  const auto t0 = Clock::now();
  const Template tmpl = load_template(a.template_path);
  const Variant variant = a.seed >= 0 ? make_variant(tmpl, static_cast<uint64_t>(a.seed))
                                      : Variant{tmpl, build_model(tmpl)};
  const double t_model = seconds_since(t0);
  const double voxel_m =
      a.voxel > 0 ? a.voxel * tmpl.metres_per_unit : default_voxel_length(variant.model);
  // The grid and its cost, before any work.
  Outcome<InteriorVolume> grid = volume_grid(variant.model, voxel_m);
  if (!grid) throw UsageError("--voxel: " + grid.reason());
  if (const Check cost = check_volume_rays(static_cast<double>(grid->voxels()), a.cube); !cost)
    throw UsageError("--voxel: " + cost.reason() + "; " +
                     coarser_grid_advice(variant.model, tmpl.metres_per_unit, a.cube));
  spdlog::info("{}: sampling {} x {} x {} voxels of {:.3g} mm (PMVC at every solid one)", tmpl.name,
               grid->size.x, grid->size.y, grid->size.z, voxel_m * 1e3);
  const uint64_t modulation_seed = a.seed >= 0 ? static_cast<uint64_t>(a.seed) : 0;
  const ColourModulation modulation(tmpl.npr, modulation_seed);
  const auto diffusion = diffusion_factory(a.cube, common)(variant.model);
  const InteriorVolume volume = sample_interior_volume(variant.model, *diffusion, std::move(*grid),
                                                       common.threads, &modulation, a.perlin);
  spdlog::info("{}: {} solid voxels in {} regions, {} of them sampled inside a grain that "
               "misses their centre and {} inside a layer their grid line misses (classify "
               "{:.1f} s, PMVC {:.1f} s)",
               tmpl.name, volume.solid, volume.regions, volume.grain_samples, volume.layer_samples,
               volume.seconds_classify, volume.seconds_diffuse);

  const auto t1 = Clock::now();
  std::string vdb_name;
  if (!paths.vdb.empty()) {
    write_file_atomically(vdb_file, encode_vdb(volume, tmpl.name, a.seed));
    spdlog::info("wrote {}", paths.vdb);
  }
  if (!paths.sidecar.empty()) {
    const Outcome<VolumeFlipbooks> encoded = encode_flipbooks(volume);
    if (!encoded) throw UsageError("--voxel: " + encoded.reason() + "; give a longer voxel");
    const VolumeFlipbooks& flipbooks = *encoded;
    write_file_atomically(colour_file, flipbooks.colour);
    write_file_atomically(structure_file, flipbooks.structure);
    write_file_atomically(material_file, flipbooks.material);
    VolumeFileNames names;
    names.colour = relative_to(flipbook_path(paths.sidecar, "colour"), paths.sidecar);
    names.structure = relative_to(flipbook_path(paths.sidecar, "structure"), paths.sidecar);
    names.material = relative_to(flipbook_path(paths.sidecar, "material"), paths.sidecar);
    if (!paths.vdb.empty()) names.vdb = relative_to(paths.vdb, paths.sidecar);
    write_file_atomically(sidecar_file,
                          volume_sidecar(volume, tmpl.name, a.seed, names).dump(2) + "\n");
    spdlog::info("wrote {} and its flipbooks ({} + {} + {} bytes)", paths.sidecar,
                 flipbooks.colour.size(), flipbooks.structure.size(), flipbooks.material.size());
  }
  if (!paths.gltf.empty()) {
    const SceneAssets assets = whole_object_assets(variant, *diffusion, a.perlin, modulation_seed);
    GltfSceneOptions gltf = export_options("quantize", 0, "jpeg");
    gltf.camera_and_lights = false;
    nlohmann::json reference = {{"voxel_m", volume.voxel_m},
                                {"size", {volume.size.x, volume.size.y, volume.size.z}},
                                {"first_centre_m",
                                 {volume.origin.x, volume.origin.y, volume.origin.z}}};
    if (!paths.sidecar.empty()) reference["sidecar"] = relative_to(paths.sidecar, paths.gltf);
    if (!paths.vdb.empty()) reference["vdb"] = relative_to(paths.vdb, paths.gltf);
    gltf.scene_extras["interior_volume"] = reference;
    write_outputs(assets, targets, common.threads, 0.0, gltf);
  }
  if (common.stats) {
    *common.stats = {{"template", tmpl.name},
                     {"backend", diffusion->name()},
                     {"voxel_m", volume.voxel_m},
                     {"voxels", volume.voxels()},
                     {"solid_voxels", volume.solid},
                     {"regions", volume.regions},
                     {"rays", diffusion->rays_cast()},
                     {"seconds",
                      {{"model", t_model},
                       {"classify", volume.seconds_classify},
                       {"diffuse", volume.seconds_diffuse},
                       {"write", seconds_since(t1)}}}};
  }
  return 0;
}

}  // namespace

Command add_volume_command(CLI::App& app) {
  auto args = std::make_shared<VolumeArgs>();
  CLI::App* volume = app.add_subcommand(
      "volume", "the interior as a volume: OpenVDB, flipbook PNGs + JSON, glTF referring to them");
  volume->add_option("TEMPLATE", args->template_path, "template file (.yaml)")->required();
  volume
      ->add_option("-o,--output", args->outputs,
                   "OUT.vdb, OUT.json (with OUT.colour/.structure/.material.png beside it), "
                   "OUT.glb/.gltf (the whole object, the volume in its extras), or OUT without "
                   "extension for all three; repeatable")
      ->required();
  volume->add_option("--seed", args->seed, "the random variant of this seed")->check(seed_rule());
  volume
      ->add_option("--voxel", args->voxel,
                   "voxel edge in template units (default: the skin's longest edge / " +
                       std::to_string(kDefaultVoxelsAcross) +
                       "); a grid that would cast more rays than the default grid of a "
                       "cube-shaped skin is refused")
      ->check(positive_number_rule());
  volume->add_option("--cube", args->cube, "cube-map texels per face edge for PMVC")
      ->check(number_rule(2, 256));
  volume->add_option("--perlin", args->perlin, "Perlin colour modulation strength (0: none)")
      ->check(number_rule(0.0, 10.0));
  return {volume, [args](const Common& common, OutputSet& outputs) {
            return run_volume(*args, common, outputs);
          }};
}

}  // namespace cutaway::cli
