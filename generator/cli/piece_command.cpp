// `cutaway piece`: one object (or a seeded variant) cut into pieces, written as glTF or POV-Ray
// and pictured pulled apart; and the cut helpers `sheet` shares. Argument checks and calls into
// the libraries only.
#include <chrono>
#include <string>

#include <spdlog/spdlog.h>

#include "base/error.h"
#include "base/timer.h"
#include "cli/commands.h"
#include "cli/scene_outputs.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "render/diffusion_backends.h"
#include "scene/collision_shape.h"
#include "scene/piece_views.h"
#include "variation/variation.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

CutSpec checked_cut(const Template& tmpl, const std::string& text, const std::string& what) {
  const Outcome<CutSpec> parsed = parse_cut_spec(text, tmpl.metres_per_unit);
  if (!parsed) throw UsageError(what + ": " + parsed.reason());
  const CutSpec cut = *parsed;
  const long long estimate = estimate_piece_count(cut, template_extents(tmpl));
  if (estimate > kMaxPiecesPerCut)
    throw UsageError(what + ": would make about " + std::to_string(estimate) +
                     " pieces (at most " + std::to_string(kMaxPiecesPerCut) + ")");
  return cut;
}

DiffusionFactory diffusion_factory(int cube, const Common& common) {
  const DiffusionChoice choice = parse_diffusion_choice(common.backend);
  const DiffusionOptions options{cube, common.threads, true, common.adaptive_directions};
  return [options, choice](const DsModel& model) {
    return make_diffusion(model, options, choice);
  };
}

CutObject cut_for_view(SceneAssets& assets, const Variant& variant, const CutSpec& cut, int cube,
                       const Common& common, double perlin, uint64_t seed,
                       const std::string& what) {
  const PieceMaterials materials = add_piece_materials(
      assets, variant.tmpl.name, variant.tmpl.skin_material, variant.tmpl.cut_material);
  ObjectCutOptions options;
  options.cut = cut;
  options.whole_when_missed = false;
  options.modulation_seed = seed;
  options.perlin = perlin;
  options.sampling = common.sampling;
  options.cap_colours = CapColours::Vertex;
  ObjectCutStats stats;
  Outcome<CutObject> made = cut_object(assets, variant, seed, materials,
                                       asset_name(variant.tmpl.name),
                                       *diffusion_factory(cube, common)(variant.model), options,
                                       stats);
  if (!made) throw UsageError(what + ": " + made.reason());
  return std::move(*made);
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
  const Variant variant = a.seed >= 0 ? make_variant(tmpl, static_cast<uint64_t>(a.seed))
                                      : Variant{tmpl, build_model(tmpl)};
  const double t_model = seconds_since(t0);
  const auto t1 = Clock::now();
  // Perlin colour modulation in the object frame: the variant's seed, or 0 for the template.
  SceneAssets assets;
  assets.name = tmpl.name;
  const CutObject object =
      cut_for_view(assets, variant, cut, a.cube, common, a.perlin,
                   a.seed >= 0 ? static_cast<uint64_t>(a.seed) : 0, "--cut " + quoted(a.cut));
  const PieceSet& set = object.set;
  const double t_cut = seconds_since(t1);
  size_t triangles = 0;
  for (const AssetMesh& mesh : object.meshes) triangles += mesh.triangle.size();
  spdlog::info("{}: {} pieces, {} triangles, {} cut planes", tmpl.name, set.pieces.size(),
               triangles, set.cells.planes.size());
  if (set.attempts > 1)
    spdlog::info("the cut was redone {} times with its planes nudged (near-degenerate position)",
                 set.attempts - 1);
  if (set.defective_pieces > 0)
    spdlog::warn("{} pieces are not closed 2-manifolds", set.defective_pieces);
  assets = piece_assets(std::move(assets), object, 0.3, a.width, a.height);
  GltfSceneOptions gltf = export_options(a.compress, a.lods, a.textures);
  gltf.camera_and_lights = a.camera_and_lights;  // an asset leaves them out unless asked
  gltf.collision = parse_gltf_collision(a.collision);
  CUTAWAY_CHECK(assets.instances.size() == object.shapes.size());  // piece k is instance k
  if (gltf.collision != GltfCollision::None)
    for (size_t k = 0; k < object.shapes.size(); ++k)
      assets.instances[k].collision = collision_hulls(object.shapes[k]);
  const Written w = write_outputs(assets, targets, common.threads, a.silhouettes, gltf);
  if (common.stats) {
    *common.stats = {{"template", tmpl.name},
                     {"backend", object.backend},
                     {"pieces", set.pieces.size()},
                     {"planes", set.cells.planes.size()},
                     {"triangles", triangles},
                     {"diffused_points", set.diffused.all},
                     {"seconds",
                      {{"model", t_model},
                       {"cut", t_cut},
                       {"sections", set.seconds_sections},
                       {"diffuse", set.seconds_diffuse},
                       {"clip", set.seconds_clip},
                       {"strokes", w.strokes_s},
                       {"export", w.export_s},
                       {"png", w.preview_s}}}};
  }
  return 0;
}

}  // namespace cutaway::cli
