// `cutaway piece`: one object (or a seeded variant) cut into pieces, written as glTF or POV-Ray
// and pictured pulled apart; and the cut helpers `sheet` shares. Argument checks and calls into
// the libraries only.
#include <chrono>
#include <memory>
#include <string>

#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "app/cli/scene_outputs.h"
#include "base/error.h"
#include "base/timer.h"
#include "cut/piece_views.h"
#include "diffusion/diffusion.h"
#include "io/cut_notation.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "export/engine_profile.h"
#include "placement/collision_shape.h"
#include "render/diffusion_backends.h"
#include "variation/variation.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// `cutaway piece TEMPLATE --cut SPEC [--seed S] [-o pieces.glb|.gltf|.pov] [--png p.png]`.
struct PieceArgs {
  std::string template_path, cut, output, png;
  int64_t seed = -1;  ///< >= 0: cut the variant of this seed instead of the template
  int width = 800, height = 600;
  int cube = kDefaultCubeSize;
  double perlin = 1.0;             ///< Perlin colour modulation strength (the template's npr bands)
  double apart = 0.3;              ///< --apart: how far the pieces are pulled apart (piece_assets)
  StyleArgs style;                 ///< --style, --silhouettes: strokes over the PNG and in .pov
  std::string compress;            ///< glTF vertex data: none, quantize or meshopt; empty: the
                                   ///< profile's, else quantize
  int lods = 0;                    ///< glTF levels of detail per mesh (GltfSceneOptions)
  std::string textures = "jpeg";   ///< texture images: jpeg, png or ktx2 (TextureFormat)
  bool texture_fallback = false;   ///< --texture-fallback: JPEG/PNG beside KTX2
  bool camera_and_lights = false;  ///< --camera-and-lights: write them into the glTF
  std::string collision;           ///< --collision: none, godot, unreal or godot-rigid; empty: the
                                   ///< profile's, else godot
  std::string engine;              ///< --for: an engine profile (engine_profile.h), empty: none
  std::string colours = "texture";  ///< --colours: texture or vertex (CapColours)
};

int run_piece(const PieceArgs& a, const Common& common, OutputSet& outputs) {
  if (a.output.empty() && a.png.empty()) throw UsageError("give -o and/or --png");
  if (!a.output.empty()) output_format("-o", a.output);
  if (!a.png.empty()) require_extension("--png", a.png, ".png");
  std::vector<std::string> exports;
  if (!a.output.empty()) exports.push_back(a.output);
  const Targets targets = register_outputs(outputs, exports, a.png, "");
  GltfSceneOptions gltf = export_options("quantize", a.lods, a.textures, a.texture_fallback);
  gltf.camera_and_lights = a.camera_and_lights;  // an asset leaves them out unless asked
  gltf.collision = GltfCollision::Godot;
  if (!a.engine.empty()) apply_engine_profile(a.engine, gltf);  // then what is given over it
  if (!a.compress.empty()) gltf.compression = parse_gltf_compression(a.compress);
  if (!a.collision.empty()) gltf.collision = parse_gltf_collision(a.collision);
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
                   a.seed >= 0 ? static_cast<uint64_t>(a.seed) : 0, "--cut " + quoted(a.cut),
                   a.colours == "vertex" ? CapColours::Vertex : CapColours::Texture);
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
  assets = piece_assets(std::move(assets), object, a.apart, a.width, a.height);
  CUTAWAY_CHECK(assets.instances.size() == object.shapes.size());  // piece k is instance k
  if (writes_hull_nodes(gltf.collision)) {
    const std::vector<CollisionShape> shapes = collision_shapes(object.shapes);
    for (size_t k = 0; k < shapes.size(); ++k)
      assets.instances[k].collision = collision_hulls(shapes[k]);
  }
  const Written w = write_outputs(assets, targets, common.threads, stroke_strength(a.style), gltf);
  if (common.stats) {
    *common.stats = {{"template", tmpl.name},
                     {"backend", object.backend},
                     {"pieces", set.pieces.size()},
                     {"planes", set.cells.planes.size()},
                     {"triangles", triangles},
                     {"diffused_points", set.diffused.all},
                     {"strokes", w.strokes},
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

}  // namespace

CutSpec checked_cut(const Template& tmpl, const std::string& text, const std::string& what) {
  const Outcome<CutSpec> parsed = parse_cut_spec(text, tmpl.metres_per_unit);
  if (!parsed) throw UsageError(what + ": " + parsed.reason());
  const CutSpec cut = *parsed;
  const long long estimate = estimate_piece_count(cut, template_extents(tmpl));
  if (estimate > kMaxPiecesPerCut)
    throw UsageError(what + ": would make about " + std::to_string(estimate) + " pieces (at most " +
                     std::to_string(kMaxPiecesPerCut) + ")");
  return cut;
}

DiffusionFactory diffusion_factory(int cube, const Common& common) {
  const DiffusionChoice choice = resolve_diffusion_choice(parse_diffusion_choice(common.backend));
  const DiffusionOptions options{cube, common.threads, true, common.adaptive_directions};
  return [options, choice](const DsModel& model) { return make_diffusion(model, options, choice); };
}

std::string resolved_backend(const Common& common) {
  return resolve_diffusion_choice(parse_diffusion_choice(common.backend)) == DiffusionChoice::Gl
             ? "gl"
             : "cpu";
}

Common with_resolved_backend(const Common& common) {
  Common resolved = common;
  resolved.backend = resolved_backend(common);
  return resolved;
}

std::string diffusion_settings(int cube, const Common& common) {
  return "backend=" + resolved_backend(common) + " cube=" + std::to_string(cube) +
         " directions=" + (common.adaptive_directions ? "adaptive" : "every");
}

CutObject cut_for_view(SceneAssets& assets, const Variant& variant, const CutSpec& cut, int cube,
                       const Common& common, double perlin, uint64_t seed, const std::string& what,
                       CapColours colours) {
  const PieceMaterials materials = add_piece_materials(
      assets, variant.tmpl.name, variant.tmpl.skin_material, variant.tmpl.cut_material);
  ObjectCutOptions options;
  options.cut = cut;
  options.whole_when_missed = false;
  options.modulation_seed = seed;
  options.perlin = perlin;
  options.sampling = common.sampling;
  options.cap_colours = colours;
  ObjectCutStats stats;
  Outcome<CutObject> made =
      cut_object(assets, variant, seed, materials, asset_name(variant.tmpl.name),
                 *diffusion_factory(cube, common)(variant.model), options, stats);
  if (!made) throw UsageError(what + ": " + made.reason());
  return std::move(*made);
}

Command add_piece_command(CLI::App& app) {
  auto args = std::make_shared<PieceArgs>();
  CLI::App* piece = app.add_subcommand(
      "piece", "cut one object into pieces with diffused cut faces (glb/gltf/pov, PNG)");
  piece->add_option("TEMPLATE", args->template_path, "template file (.yaml)")->required();
  piece
      ->add_option("--cut", args->cut,
                   "halves, slices:THICKNESS, wedges:COUNT, dice:SIZE, plane:SPEC or whole "
                   "(template units)")
      ->required();
  piece->add_option("--seed", args->seed, "cut the random variant of this seed")
      ->check(seed_rule());
  piece->add_option("-o,--output", args->output, "pieces to write: .glb, .gltf or .pov");
  piece->add_option("--png", args->png, "PNG of the pieces pulled slightly apart");
  piece->add_option("--cube", args->cube, "cube-map texels per face edge for PMVC")
      ->check(number_rule(2, 256));
  piece
      ->add_option("--perlin", args->perlin,
                   "Perlin colour modulation strength (0: off; default 1)")
      ->check(number_rule(0.0, 10.0));
  piece
      ->add_option("--apart", args->apart,
                   "how far the pieces are pulled apart from the object's centre, in the files "
                   "and the PNG (0: assembled as cut; default 0.3)")
      ->check(number_rule(0.0, 2.0));
  add_style_options(piece, args->style, "over the PNG and in .pov");
  add_export_options(piece, args->compress, args->lods, args->textures, args->texture_fallback);
  add_colours_option(piece, args->colours);
  piece->add_flag("--camera-and-lights", args->camera_and_lights,
                  "write the preview's camera and studio lights into the glTF file (an asset "
                  "leaves them out by default: it goes into someone else's scene)");
  piece
      ->add_option("--collision", args->collision,
                   "convex collision hulls of each piece in the glTF file, named for godot "
                   "(NAME_collisionK-convcolonly, the default), unreal (UCX_MESH_KK) or none; "
                   "godot-rigid: no hulls, each piece's mesh a Godot RigidBody (NAME_mesh-rigid)")
      ->check(CLI::IsMember({"none", "godot", "unreal", "godot-rigid"}));
  add_engine_option(piece, args->engine,
                    "the consumer the glTF file is for, which sets --compress and --collision "
                    "(given ones win) and pivots: godot (float32, one RigidBody per piece "
                    "turning about its centre of mass), unreal (float32, UCX_ hulls, pivots at "
                    "the centres of mass), unity (quantize, no hulls, the same pivots), web "
                    "(meshopt, no hulls) or blender "
                    "(quantize, no hulls); doc/engines.md");
  return {piece, [args](const Common& common, OutputSet& outputs) {
            return run_piece(*args, common, outputs);
          }};
}

}  // namespace cutaway::cli
