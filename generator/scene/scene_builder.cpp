#include "scene/scene_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <oneapi/tbb/parallel_pipeline.h>

#include "assets/asset_camera.h"
#include "assets/backdrop.h"
#include "base/constants.h"
#include "base/error.h"
#include "base/random.h"
#include "base/timer.h"
#include "cache/cached_cut.h"
#include "cache/cached_placement.h"
#include "cache/cut_entry_check.h"
#include "placement/collision_shape.h"
#include "placement/board_wood.h"
#include "placement/container_mesh.h"
#include "placement/physics_settle.h"
#include "placement/scene_layout.h"
#include "variation/variation.h"

namespace cutaway {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

glm::dvec3 default_view_direction() {
  return {0, std::sin(glm::radians(50.0)), std::cos(glm::radians(50.0))};
}

glm::dvec3 scene_view_direction(const Scene& scene) {
  return scene.camera ? glm::normalize(scene.camera->eye - scene.camera->target)
                      : default_view_direction();
}

uint64_t object_seed(uint64_t scene_seed, int item, int object, int purpose) {
  return derive_seed(scene_seed, {static_cast<uint64_t>(item), static_cast<uint64_t>(object),
                                  static_cast<uint64_t>(purpose)});
}

AssetCamera scene_camera(const Scene& scene, const glm::dvec3& pile_min,
                         const glm::dvec3& pile_max) {
  const double aspect = static_cast<double>(scene.render.width) / scene.render.height;
  if (!scene.camera) return frame_box(pile_min, pile_max, default_view_direction(), 40, aspect);
  AssetCamera cam;
  cam.eye = scene.camera->eye;
  cam.target = scene.camera->target;
  cam.up = stable_camera_up(cam.target - cam.eye);
  cam.fov_y_deg = scene.camera->fov_deg;
  cam.aspect = aspect;
  const double distance = glm::distance(cam.eye, cam.target);
  const double extent = glm::distance(pile_min, pile_max);
  cam.znear = std::max(1e-4, 0.02 * distance);
  cam.zfar = distance + 4 * extent + 1;
  return cam;
}

namespace {

/// Every kept piece of a scene's objects in the object frame, in item and object order.
struct ScenePieces {
  std::vector<ShadedMesh> shapes;     // as cut (layout, physics)
  std::vector<AssetMesh> meshes;      // as exported, once placed
  std::vector<LayoutPiece> arranged;  // cap, arrangement, row (mesh set by the layout step)
  std::vector<double> densities;      // kg/m^3
  std::vector<PieceInfo> infos;
  std::vector<CollisionShape> collision;
  std::vector<std::string> cut_keys;  // per object: its cut_cache_key
  std::vector<Arrangement> arrange;   // per object
};

/// The options of cut_object() for object `j` of item `i`.
ObjectCutOptions object_cut_options(const Scene& scene, uint64_t seed,
                                    const SceneBuildOptions& options, size_t i, int j) {
  const SceneItem& item = scene.items[i];
  const int ii = static_cast<int>(i);
  ObjectCutOptions cut;
  cut.cut = item.cut;
  cut.keep = item.keep;
  cut.keep_seed = object_seed(seed, ii, j, 2);
  cut.modulation_seed = object_seed(seed, ii, j, 3);
  cut.perlin = scene.render.perlin;
  cut.sampling = options.sampling;
  cut.cap_colours = options.cap_colours;
  cut.atlas = options.atlas;
  if (cut.atlas.texels_per_m == 0) cut.atlas.texels_per_m = 1000 * scene.render.texels_per_mm;
  cut.skin = options.skin;
  return cut;
}

/// One object of a scene to cut: its item, its index in the item, and what its cut needs.
struct ObjectJob {
  size_t item = 0;
  int index = 0;  ///< in the item
  uint64_t variant_seed = 0;
  ObjectCutOptions cut;
  std::string name;  ///< the object's asset name
  std::string key;   ///< cut_cache_key
};

/// The cut counts and timings of `from` added to `to`.
void add_cut_stats(SceneStats& to, const SceneStats& from) {
  to.diffused += from.diffused;
  to.recut_objects += from.recut_objects;
  to.defective_pieces += from.defective_pieces;
  to.seconds_sections += from.seconds_sections;
  to.seconds_diffuse += from.seconds_diffuse;
  to.seconds_clip += from.seconds_clip;
  to.seconds_bake += from.seconds_bake;
  to.seconds_variants += from.seconds_variants;
  to.seconds_backend += from.seconds_backend;
  to.seconds_collision += from.seconds_collision;
}

/// The cache entry of one object (make_cut_entry): a seeded variant of its item's template,
/// cut (cut_object). Touches nothing shared: objects are made side by side.
CutEntry make_object_entry(const Template& tmpl, const ObjectJob& job,
                           const SceneBuildOptions& options, SceneStats& st) {
  CutEntry entry = make_cut_entry(
      options.cache, job.key, tmpl, &options.collision,
      [&](SceneAssets& own, const PieceMaterials& materials) {
        const auto t0 = Clock::now();
        const Variant variant = make_variant(tmpl, job.variant_seed);
        st.seconds_variants += seconds_since(t0);
        const auto t_backend = Clock::now();
        const std::unique_ptr<DiffusionBackend> diffusion = options.diffusion(variant.model);
        st.seconds_backend += seconds_since(t_backend);
        return CutPieces(std::move(*cut_object(own, variant, job.variant_seed, materials, job.name,
                                               *diffusion, job.cut, st)));
      });
  st.seconds_collision += entry.seconds_collision;
  return entry;
}

/// Adds one object's entry to the scene: its materials and textures to `assets` (the item's
/// own materials first, at its first object), its kept pieces to `out`; reports progress (of
/// `objects` in all).
void add_object(const Scene& scene, const std::vector<Template>& templates, const ObjectJob& job,
                const CutEntry& entry, int objects, const SceneBuildOptions& options,
                SceneAssets& assets, PieceMaterials& item_materials, ScenePieces& out,
                SceneStats& st) {
  const SceneItem& item = scene.items[job.item];
  const Template& tmpl = templates[job.item];
  if (job.index == 0)
    item_materials = add_piece_materials(assets, tmpl.name, tmpl.skin_material, tmpl.cut_material);
  CachedCut made = add_cut_entry(entry, assets, item_materials);
  st.cached_objects += made.from_cache;
  out.cut_keys.push_back(job.key);
  out.arrange.push_back(item.arrange);
  CutPieces& p = made.pieces;
  for (size_t q = 0; q < p.meshes.size(); ++q) {
    out.meshes.push_back(std::move(p.meshes[q]));
    out.shapes.push_back(std::move(p.shapes[q]));
    out.arranged.push_back(
        {nullptr, p.cap_normals[q], item.arrange, st.objects, p.infos[q].cell, p.cut_faces[q]});
    out.densities.push_back(tmpl.density_kg_m3);
    out.infos.push_back(std::move(p.infos[q]));
    out.collision.push_back(std::move(made.collision[q]));
  }
  ++st.objects;
  if (options.progress)
    options.progress(st.objects, objects,
                     tmpl.name + " " + std::to_string(job.index + 1) + "/" +
                         std::to_string(item.count) + ": " + std::to_string(p.meshes.size()) +
                         " of " + std::to_string(p.pieces_cut) + " pieces" +
                         (made.from_cache ? " (cut cache)" : ""));
}

/// Step 1: every object of every item as a seeded variant, cut (cut_object), a seeded share
/// of its pieces kept, with their collision shapes; the templates' materials and the baked
/// textures go into `assets`. Objects the cut cache holds are read from it instead. Up to
/// options.objects_at_once objects are made side by side, then added in item and object order.
ScenePieces cut_scene_objects(const Scene& scene, uint64_t seed, const SceneBuildOptions& options,
                              SceneAssets& assets, SceneStats& st) {
  std::vector<Template> templates;  // per item, its variation scaled
  std::vector<ObjectJob> jobs;
  for (size_t i = 0; i < scene.items.size(); ++i) {
    const SceneItem& item = scene.items[i];
    CUTAWAY_CHECK(item.tmpl);  // load_scene read it
    templates.push_back(*item.tmpl);
    Template& tmpl = templates.back();
    tmpl.variation_amount *= item.variation;
    for (int j = 0; j < item.count; ++j) {
      // Appended rather than "i" + ...: GCC 12 warns of an overlapping copy there (-Wrestrict,
      // a false positive).
      std::string name = "i";
      name += std::to_string(i) + "_" + asset_name(tmpl.name) + "_" + std::to_string(j);
      ObjectJob job{i,
                    j,
                    object_seed(seed, static_cast<int>(i), j, 1),
                    object_cut_options(scene, seed, options, i, j),
                    std::move(name),
                    {}};
      job.key = cut_cache_key({tmpl.source_hash, tmpl.variation_amount, job.variant_seed, job.name,
                               options.diffusion_settings, &job.cut, &options.collision});
      jobs.push_back(std::move(job));
    }
  }
  ScenePieces out;
  PieceMaterials item_materials;
  // A pipeline: up to objects_at_once objects in the making at a time, each starting as soon as
  // one before it is done (no object waits for the slowest of a group), added in order.
  struct Made {
    size_t job = 0;
    CutEntry entry;
    SceneStats stats;
  };
  using MadePtr = std::shared_ptr<Made>;
  namespace tbb = oneapi::tbb;
  size_t next = 0;
  tbb::parallel_pipeline(
      static_cast<size_t>(std::max(1, options.objects_at_once)),
      tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order,
                                     [&](tbb::flow_control& control) -> size_t {
                                       if (next == jobs.size()) control.stop();
                                       return next++;
                                     }) &
          tbb::make_filter<size_t, MadePtr>(tbb::filter_mode::parallel,
                                            [&](size_t k) {
                                              auto made = std::make_shared<Made>();
                                              made->job = k;
                                              made->entry =
                                                  make_object_entry(templates[jobs[k].item],
                                                                    jobs[k], options, made->stats);
                                              return made;
                                            }) &
          tbb::make_filter<MadePtr, void>(tbb::filter_mode::serial_in_order, [&](MadePtr made) {
            add_object(scene, templates, jobs[made->job], made->entry,
                       static_cast<int>(jobs.size()), options, assets, item_materials, out, st);
            add_cut_stats(st, made->stats);
          }));
  st.pieces = static_cast<int>(out.shapes.size());
  return out;
}

/// The pieces in `order` dropped by the height-field layout, then settled as rigid bodies
/// from those poses; one placement per entry of `order`.
SettleResult lay_out_and_settle(const Scene& scene, uint64_t seed, const SettleOptions& settle,
                                const LayoutOptions& layout_options, const ScenePieces& pieces,
                                const std::vector<size_t>& order, SceneStats& st) {
  const auto t0 = Clock::now();
  std::vector<LayoutPiece> layout;
  for (size_t k : order) {
    layout.push_back(pieces.arranged[k]);
    layout.back().mesh = &pieces.shapes[k];
  }
  const std::vector<Placement> drops =
      layout_pieces(layout, scene.container, layout_options, derive_seed(seed, {~0ull, 4}));
  st.seconds_layout = seconds_since(t0);

  const auto t_physics = Clock::now();
  std::vector<SettleBody> bodies(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    if (!drops[k].placed) continue;
    const LayoutPiece& piece = pieces.arranged[order[k]];
    // A piece with one cut face rests showing it; a slice shows one of its two whichever way.
    const glm::dvec3 cut_face = piece.cut_faces == 1 ? piece.cap_normal : glm::dvec3(0.0);
    bodies[k] = {&pieces.collision[order[k]], pieces.densities[order[k]], drops[k], cut_face};
  }
  SettleResult settled = settle_pieces(bodies, scene.container, settle);
  st.seconds_physics = seconds_since(t_physics);
  return settled;
}

/// The turn about +Y (radians, counter-clockwise seen from above).
glm::dquat turn_about_y(double angle) { return glm::angleAxis(angle, glm::dvec3(0, 1, 0)); }

/// Step 2: the pieces' placements in `order` (lay_out_and_settle), read from the cut cache when
/// it holds those of the same objects, arrangement, seed, container and options.
std::vector<Placement> place_pieces(const Scene& scene, uint64_t seed,
                                    const SceneBuildOptions& options, const ScenePieces& pieces,
                                    const std::vector<size_t>& order, SceneStats& st) {
  const LayoutView view = layout_view(scene.container, scene_view_direction(scene));
  LayoutOptions layout_options = options.layout;
  layout_options.to_camera = view.to_camera;
  SettleOptions settle = options.settle;  // the cut faces must end turned to the same camera
  settle.to_camera = view.to_camera;
  std::string key;
  std::optional<SettleResult> cached;
  if (options.cache) {
    key = placement_cache_key(
        {pieces.cut_keys, pieces.arrange, seed, &scene.container, &layout_options, &settle});
    if (std::optional<std::string> payload = options.cache->load(key)) {
      // Untrusted input: checked against this scene's pieces and container, else made again.
      cached = decode_settled(*payload, order.size());
      const Check usable =
          cached ? check_cached_placements(cached->placements, order.size(), scene.container,
                                           options.settle.none_radius_m)
                 : Check::none("it is not the placements of this scene's " +
                               std::to_string(order.size()) + " pieces");
      if (!usable) {
        options.cache->discard(key, usable.reason());
        cached.reset();
      }
    }
  }
  st.cached_placements = cached.has_value();
  SettleResult settled =
      cached ? std::move(*cached)
             : lay_out_and_settle(scene, seed, settle, layout_options, pieces, order, st);
  if (options.cache && !cached) options.cache->store(key, encode_settled(settled));
  for (size_t k = 0; k < order.size(); ++k)
    if (settled.placements[k].placed) st.decomposed_pieces += pieces.collision[order[k]].decomposed;
  if (view.turn_back != 0) {
    const glm::dquat turn = turn_about_y(view.turn_back);
    for (Placement& place : settled.placements) {
      place.rotation = turn * place.rotation;
      place.translation = turn * place.translation;
    }
  }
  st.simulated_seconds = settled.simulated_s;
  st.settled = settled.all_asleep;
  st.redropped = settled.redrops;
  st.lost = settled.lost;
  st.stability_motion_m = settled.stability_motion_m;
  st.stability_checks = settled.verify_rounds;
  st.stability_kept_check = settled.kept_round;
  return std::move(settled.placements);
}

/// Gives `mesh` a new material of `assets` for all its triangles: `name`, of perceptual
/// `roughness`, its base colour the texture of index `texture` (or the vertex colours, -1).
void give_material(SceneAssets& assets, AssetMesh& mesh, const char* name, double roughness,
                   int texture = -1) {
  assets.materials.push_back({name, PbrMaterial{}, texture});
  assets.materials.back().pbr.roughness = roughness;
  mesh.primitives = {{0, mesh.triangle.size(), static_cast<int>(assets.materials.size()) - 1, {}}};
}

/// Step 3: the container (a board with its wood, drawn from `seed`; a bowl or plate glazed) and
/// the placed pieces as instances of `assets`, framed by the scene's camera, on the scene's
/// backdrop (not framed), with the studio lights.
void add_placed_pieces(SceneAssets& assets, const Scene& scene, uint64_t seed, ScenePieces& pieces,
                       const std::vector<size_t>& order, const std::vector<Placement>& placements,
                       SceneStats& st) {
  assets.name = scene.name;
  assets.width = scene.render.width;
  assets.height = scene.render.height;
  assets.background = {0.72, 0.72, 0.74};
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  if (auto container = container_mesh(scene.container)) {
    for (const glm::dvec3& p : container->position) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    if (scene.container.type == ContainerType::Board) {  // its wood, on its uv
      assets.textures.push_back(board_wood_texture(scene.container, derive_seed(seed, {~0ull, 7})));
      // Oiled, worn wood: a broad, faint highlight.
      give_material(assets, *container, "board_wood", 0.75,
                    static_cast<int>(assets.textures.size()) - 1);
    } else {  // a bowl or plate: glazed ceramic, a sharp highlight over its vertex colour
      give_material(assets, *container, "glazed_ceramic", 0.15);
    }
    assets.instances.push_back({container->name, 0, {1, 0, 0, 0}, {0, 0, 0}, {}});
    assets.meshes.push_back(std::move(*container));
  }
  for (size_t k = 0; k < order.size(); ++k) {
    const Placement& place = placements[k];
    if (!place.placed) continue;
    const size_t s = order[k];
    for (const glm::dvec3& p : pieces.shapes[s].position) {
      const glm::dvec3 q = place.translation + place.rotation * p;
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    assets.instances.push_back({pieces.meshes[s].name, static_cast<int>(assets.meshes.size()),
                                place.rotation, place.translation, pieces.infos[s]});
    assets.meshes.push_back(std::move(pieces.meshes[s]));
    ++st.placed;
  }
  if (assets.instances.empty()) lo = hi = glm::dvec3(0.0);
  assets.camera = scene_camera(scene, lo, hi);
  std::optional<AssetMesh> backdrop;  // framed by the camera, not framing it
  if (scene.backdrop.sweep) backdrop = backdrop_sweep(assets.camera, lo, hi, scene.backdrop.colour);
  if (backdrop) {
    AssetMesh& sweep = *backdrop;
    assets.camera.zfar = std::max(assets.camera.zfar, 1.01 * farthest_vertex(assets.camera, sweep));
    give_material(assets, sweep, "backdrop", 0.9);  // matte paper
    assets.instances.push_back({sweep.name,
                                static_cast<int>(assets.meshes.size()),
                                {1, 0, 0, 0},
                                {0, 0, 0},
                                {},
                                {},
                                true});
    assets.meshes.push_back(std::move(sweep));
  }
  light_like_studio(assets);
}

}  // namespace

SceneAssets build_scene(const Scene& scene, uint64_t seed, const SceneBuildOptions& options,
                        SceneStats* stats) {
  if (!options.diffusion) throw InternalError("build_scene: no diffusion backend");
  if (options.cache && options.diffusion_settings.empty())
    throw InternalError("build_scene: a cut cache without the diffusion settings of its keys");
  SceneStats local;
  SceneStats& st = stats ? *stats : local;
  st = SceneStats{};
  SceneAssets assets;
  ScenePieces pieces = cut_scene_objects(scene, seed, options, assets, st);
  const std::vector<size_t> order = placement_order(pieces.shapes.size(), seed);
  const std::vector<Placement> placements = place_pieces(scene, seed, options, pieces, order, st);
  add_placed_pieces(assets, scene, seed, pieces, order, placements, st);
  st.triangles = drawn_triangles(assets);
  return assets;
}

}  // namespace cutaway
