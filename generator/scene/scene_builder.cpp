#include "scene/scene_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "assets/asset_camera.h"
#include "base/constants.h"
#include "base/error.h"
#include "base/random.h"
#include "base/timer.h"
#include "placement/collision_shape.h"
#include "placement/container_mesh.h"
#include "placement/physics_settle.h"
#include "variation/variation.h"

namespace cutaway {

namespace {

using Clock = std::chrono::steady_clock;

/// The default view: from the front (+Z), 50 degrees above the horizon.
const glm::dvec3 kDefaultToCamera(0, std::sin(glm::radians(50.0)), std::cos(glm::radians(50.0)));

}  // namespace

uint64_t object_seed(uint64_t scene_seed, int item, int object, int purpose) {
  return derive_seed(scene_seed, {static_cast<uint64_t>(item), static_cast<uint64_t>(object),
                                  static_cast<uint64_t>(purpose)});
}

AssetCamera scene_camera(const Scene& scene, const glm::dvec3& pile_min,
                         const glm::dvec3& pile_max) {
  const double aspect = static_cast<double>(scene.render.width) / scene.render.height;
  if (!scene.camera) return frame_box(pile_min, pile_max, kDefaultToCamera, 40, aspect);
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
};

/// Step 1: every object of every item as a seeded variant, cut (cut_object), a seeded share
/// of its pieces kept; the templates' materials and the baked textures go into `assets`.
ScenePieces cut_scene_objects(const Scene& scene, uint64_t seed, const SceneBuildOptions& options,
                              SceneAssets& assets, SceneStats& st) {
  int total = 0;
  for (const SceneItem& item : scene.items) total += item.count;
  ScenePieces out;
  for (size_t i = 0; i < scene.items.size(); ++i) {
    const SceneItem& item = scene.items[i];
    CUTAWAY_CHECK(item.tmpl);  // load_scene read it
    Template tmpl = *item.tmpl;
    tmpl.variation_amount *= item.variation;
    const PieceMaterials item_materials =
        add_piece_materials(assets, tmpl.name, tmpl.skin_material, tmpl.cut_material);
    for (int j = 0; j < item.count; ++j) {
      const int ii = static_cast<int>(i);
      const auto t0 = Clock::now();
      const uint64_t variant_seed = object_seed(seed, ii, j, 1);
      const Variant variant = make_variant(tmpl, variant_seed);
      st.seconds_variants += seconds_since(t0);
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
      const std::string object =
          "i" + std::to_string(i) + "_" + asset_name(tmpl.name) + "_" + std::to_string(j);
      const auto t_backend = Clock::now();
      const std::unique_ptr<DiffusionBackend> diffusion = options.diffusion(variant.model);
      st.seconds_backend += seconds_since(t_backend);
      CutObject made = *cut_object(assets, variant, variant_seed, item_materials, object,
                                   *diffusion, cut, st);
      for (size_t q = 0; q < made.kept.size(); ++q) {
        const Piece& piece = made.set.pieces[made.kept[q]];
        out.meshes.push_back(std::move(made.meshes[q]));
        out.shapes.push_back(std::move(made.shapes[q]));
        out.arranged.push_back({nullptr, largest_cap_normal(piece), item.arrange, st.objects,
                                piece.cell, cut_faces(piece)});
        out.densities.push_back(tmpl.density_kg_m3);
        out.infos.push_back(std::move(made.infos[q]));
      }
      ++st.objects;
      if (options.progress)
        options.progress(st.objects, total,
                         tmpl.name + " " + std::to_string(j + 1) + "/" +
                             std::to_string(item.count) + ": " + std::to_string(made.kept.size()) +
                             " of " + std::to_string(made.set.pieces.size()) + " pieces");
    }
  }
  st.pieces = static_cast<int>(out.shapes.size());
  return out;
}

/// The pieces' indices in a seeded order (Fisher-Yates), so that the kinds mix in the pile.
std::vector<size_t> placement_order(size_t n, uint64_t seed) {
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  Rng rng(derive_seed(seed, {~0ull, 3}));
  for (size_t k = order.size(); k > 1; --k)
    std::swap(order[k - 1], order[rng.below(static_cast<uint32_t>(k))]);
  return order;
}

/// Step 2: the pieces in `order` dropped by the height-field layout, then settled as rigid
/// bodies from those poses; one placement per entry of `order`.
std::vector<Placement> place_pieces(const Scene& scene, uint64_t seed,
                                    const SceneBuildOptions& options, const ScenePieces& pieces,
                                    const std::vector<size_t>& order, SceneStats& st) {
  const auto t0 = Clock::now();
  std::vector<LayoutPiece> layout;
  for (size_t k : order) {
    layout.push_back(pieces.arranged[k]);
    layout.back().mesh = &pieces.shapes[k];
  }
  LayoutOptions layout_options = options.layout;
  layout_options.to_camera =
      scene.camera ? glm::normalize(scene.camera->eye - scene.camera->target) : kDefaultToCamera;
  const std::vector<Placement> drops =
      layout_pieces(layout, scene.container, layout_options, derive_seed(seed, {~0ull, 4}));
  st.seconds_layout = seconds_since(t0);

  const auto t_physics = Clock::now();
  std::vector<CollisionShape> collision(order.size());
  std::vector<SettleBody> bodies(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    if (!drops[k].placed) continue;
    collision[k] = collision_shape(pieces.shapes[order[k]], options.collision);
    st.decomposed_pieces += collision[k].decomposed;
    bodies[k] = {&collision[k], pieces.densities[order[k]], drops[k]};
  }
  SettleResult settled = settle_pieces(bodies, scene.container, options.settle);
  st.seconds_physics = seconds_since(t_physics);
  st.simulated_seconds = settled.simulated_s;
  st.settled = settled.all_asleep;
  st.redropped = settled.redrops;
  st.lost = settled.lost;
  st.stability_motion_m = settled.stability_motion_m;
  st.stability_checks = settled.verify_rounds;
  return std::move(settled.placements);
}

/// Step 3: the container and the placed pieces as instances of `assets`, framed by the
/// scene's camera, with the studio lights.
void add_placed_pieces(SceneAssets& assets, const Scene& scene, ScenePieces& pieces,
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
    st.triangles += pieces.meshes[s].triangle.size();
    assets.instances.push_back({pieces.meshes[s].name, static_cast<int>(assets.meshes.size()),
                                place.rotation, place.translation, pieces.infos[s]});
    assets.meshes.push_back(std::move(pieces.meshes[s]));
    ++st.placed;
  }
  if (assets.instances.empty()) lo = hi = glm::dvec3(0.0);
  assets.camera = scene_camera(scene, lo, hi);
  light_like_studio(assets);
}

}  // namespace

SceneAssets build_scene(const Scene& scene, uint64_t seed, const SceneBuildOptions& options,
                        SceneStats* stats) {
  if (!options.diffusion) throw InternalError("build_scene: no diffusion backend");
  SceneStats local;
  SceneStats& st = stats ? *stats : local;
  st = SceneStats{};
  SceneAssets assets;
  ScenePieces pieces = cut_scene_objects(scene, seed, options, assets, st);
  const std::vector<size_t> order = placement_order(pieces.shapes.size(), seed);
  const std::vector<Placement> placements = place_pieces(scene, seed, options, pieces, order, st);
  add_placed_pieces(assets, scene, pieces, order, placements, st);
  return assets;
}

}  // namespace cutaway
