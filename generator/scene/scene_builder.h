// The main job (doc/architecture.md, Data flow): from a parsed scene to SceneAssets ready for
// glTF, POV-Ray or the OpenGL preview. For each item and object: a seeded variant of the
// template (variation.h), cut into pieces (pieces.h), a seeded share of them kept; then all
// pieces placed in the container (scene_layout.h), with a camera and lights. Colours are
// modulated by Perlin noise in each object's frame (colour_modulation.h) with the scene's
// render.perlin strength.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "assets/scene_assets.h"
#include "cache/cut_cache.h"
#include "cut/object_cut.h"
#include "placement/physics_settle.h"
#include "placement/scene_layout.h"
#include "scene/scene.h"
#include "variation/variation.h"

namespace cutaway {

/// Options of build_scene.
struct SceneBuildOptions {
  CapColours cap_colours = CapColours::Texture;
  /// With CapColours::Texture; texels_per_m 0 (the default here): the scene's
  /// render.texels_per_mm.
  CapAtlasOptions atlas{.texels_per_m = 0};
  SkinTextureOptions skin;     ///< with CapColours::Texture: the swept skins' textures
  DiffusionFactory diffusion;  ///< required
  /// What of the diffusion backend changes colours (its resolved kind, cube size, directions),
  /// as the command line writes it: part of the cut cache's keys; required with `cache`.
  std::string diffusion_settings;
  CutCache* cache = nullptr;  ///< the cut cache (cut_cache.h), or null: every object is cut
  /// How many objects are cut side by side (each into its own assets, added to the scene in
  /// order: the output does not depend on it); 1 cuts one after another, as a backend bound to
  /// one thread (gl) needs. The stage seconds of cutting are then summed over the objects.
  int objects_at_once = 1;
  CapSampling sampling = CapSampling::Adaptive;  ///< which cap points are diffused
  /// Called after each object with (objects done, objects in all, a line of text); may be empty.
  std::function<void(int, int, const std::string&)> progress;
  LayoutOptions layout;             ///< its to_camera is replaced by the scene camera's direction
  CollisionShapeOptions collision;  ///< the pieces' rigid bodies
  SettleOptions settle;             ///< the settling; its to_camera is replaced like layout's
};

/// Counts and timings of one build_scene call (wall seconds); those of cutting the objects
/// (ObjectCutStats, variants, backends) added up over the objects, which exceeds the wall time
/// when objects are cut side by side (objects_at_once). Collision shapes are counted in
/// processor seconds instead (see seconds_collision).
struct SceneStats : ObjectCutStats {
  int objects = 0, pieces = 0, placed = 0;  ///< pieces: kept after `keep`; placed: of those
  int cached_objects = 0;                   ///< objects read from the cut cache (not cut)
  bool cached_placements = false;           ///< placements read from the cut cache (not settled)
  size_t triangles = 0;         ///< what the scene's file draws (drawn_triangles), all instances
  double seconds_variants = 0;  ///< make_variant (sweep, synthesis, grains, checks)
  double seconds_backend = 0;   ///< building the diffusion backends (BVH or GL setup)
  double seconds_layout = 0;    ///< drop poses (the height-field layout)
  /// The pieces' collision shapes (of objects not cached), in processor seconds summed over
  /// the threads that made them: the work they cost, which the wall time of objects cut side
  /// by side overstates (each waits for a core while the others run).
  double seconds_collision = 0;
  double seconds_physics = 0;    ///< settling
  double simulated_seconds = 0;  ///< simulated time of the settling
  bool settled = false;          ///< the last round of settling came to rest before its cap
  int decomposed_pieces = 0;     ///< pieces colliding as several convex parts
  int redropped = 0, lost = 0;   ///< settle_pieces: drops again; pieces left out
  /// The stability check of the placed layout: the farthest any piece's corner moved in 1 s
  /// re-simulated from rest (metres; SettleResult::stability_motion_m), the checks run and
  /// the check whose layout was kept (SettleResult::kept_round).
  double stability_motion_m = 0;
  int stability_checks = 0, stability_kept_check = 0;
};

/// The seed of item `item`, object `object`, for `purpose` (1: variant, 2: which pieces are
/// kept, 3: Perlin colour modulation): derive_seed(scene_seed, {item, object, purpose}), so adding
/// an item does not change the others (doc/scene-format.md, Determinism).
uint64_t object_seed(uint64_t scene_seed, int item, int object, int purpose);

/// The direction from the scene towards the camera of a scene without a `camera` block: from
/// the front (+Z), 50 degrees above the horizon (a unit vector).
glm::dvec3 default_view_direction();

/// The direction from the scene towards its camera (unit): from the `camera` block's target to
/// its eye, or default_view_direction() without one.
glm::dvec3 scene_view_direction(const Scene& scene);

/// The scene's camera (its `camera` block, or one framing the container and the pile from the
/// front, 50 degrees above the horizon), aspect from render width / height.
AssetCamera scene_camera(const Scene& scene, const glm::dvec3& pile_min,
                         const glm::dvec3& pile_max);

/// Builds the whole scene with `seed` (the file's seed unless the command line gives one).
/// Deterministic: the same scene, templates and seed give the same assets, whatever the
/// thread count of the diffusion backends.
/// A cut that misses an object leaves it whole.
/// @throws InputError when a template cannot be read or built
SceneAssets build_scene(const Scene& scene, uint64_t seed, const SceneBuildOptions& options,
                        SceneStats* stats = nullptr);

}  // namespace cutaway
