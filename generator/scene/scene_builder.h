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

#include "diffusion/diffusion.h"
#include "material/cap_atlas.h"
#include "material/skin_texture.h"
#include "pieces/pieces.h"
#include "scene/physics_settle.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "scene/scene_layout.h"
#include "variation/variation.h"

namespace cutaway {

/// Makes the diffusion backend for one object's DS model (the CLI's --backend choice).
using DiffusionFactory = std::function<std::unique_ptr<DiffusionBackend>(const DsModel&)>;

/// Where cut faces take their colours from.
enum class CapColours {
  Texture,  ///< a baked texture per object (bake_cap_atlas); glTF caps use TEXCOORD_0
  Vertex,   ///< the vertex colours (COLOR_0), as before textures
};

/// Options of build_scene.
struct SceneBuildOptions {
  CapColours cap_colours = CapColours::Texture;
  /// With CapColours::Texture; texels_per_m 0 (the default here): the scene's
  /// render.texels_per_mm.
  CapAtlasOptions atlas{.texels_per_m = 0};
  SkinTextureOptions skin;     ///< with CapColours::Texture: the swept skins' textures
  DiffusionFactory diffusion;  ///< required
  CapSampling sampling = CapSampling::Adaptive;  ///< which cap points are diffused
  /// Called after each object with (objects done, objects in all, a line of text); may be empty.
  std::function<void(int, int, const std::string&)> progress;
  LayoutOptions layout;        ///< its to_camera is replaced by the scene camera's direction
  CollisionShapeOptions collision;  ///< the pieces' rigid bodies
  SettleOptions settle;             ///< the settling of the layout's drop poses
};

/// Counts and timings of one build_scene call (wall seconds).
struct SceneStats {
  int objects = 0, pieces = 0, placed = 0;  ///< pieces: kept after `keep`; placed: of those
  size_t triangles = 0, diffused_points = 0;
  int recut_objects = 0;        ///< objects whose cut was redone with nudged planes
  size_t defective_pieces = 0;  ///< pieces left with a manifold defect after every attempt
  double seconds_variants = 0;  ///< make_variant (sweep, synthesis, grains, checks)
  double seconds_backend = 0;   ///< building the diffusion backends (BVH or GL setup)
  double seconds_sections = 0;  ///< cap cross-sections (triangulation + PMVC)
  double seconds_diffuse = 0;   ///< of which PMVC
  double seconds_clip = 0;      ///< clipping the skin and walls, stitching
  double seconds_bake = 0;      ///< baking cap textures
  double seconds_layout = 0;    ///< drop poses (the height-field layout)
  double seconds_physics = 0;   ///< collision shapes and settling
  double simulated_seconds = 0;     ///< simulated time of the settling
  bool settled = false;             ///< the last round of settling came to rest before its cap
  int decomposed_pieces = 0;        ///< pieces colliding as several convex parts
  int redropped = 0, lost = 0;      ///< settle_pieces: drops again; pieces left out
  /// The stability check of the placed layout: the farthest any piece's corner moved in 1 s
  /// re-simulated from rest (metres; SettleResult::stability_motion_m), and the checks run.
  double stability_motion_m = 0;
  int stability_checks = 0;
};

/// The seed of item `item`, object `object`, for `purpose` (1: variant, 2: which pieces are
/// kept, 3: Perlin colour modulation): derive_seed(scene_seed, {item, object, purpose}), so adding an item does not change
/// the others (doc/scene-format.md, Determinism).
uint64_t object_seed(uint64_t scene_seed, int item, int object, int purpose);

/// The scene's camera (its `camera` block, or one framing the container and the pile from the
/// front, 50 degrees above the horizon), aspect from render width / height.
AssetCamera scene_camera(const Scene& scene, const glm::dvec3& pile_min,
                         const glm::dvec3& pile_max);

/// A camera looking at the centre of the box lo..hi from direction `to_camera`, as close as
/// lets all eight corners of the box into the view (vertical field of view `fov_deg`, `aspect`
/// = width / height) with a 4 % margin.
AssetCamera frame_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& to_camera,
                      double fov_deg, double aspect);

/// The studio lights of every scene: a key light from above left of the camera (3 lux), a
/// fill from the right (1.2 lux) and a rim light from behind (1 lux); directional.
std::vector<AssetLight> studio_lights(const AssetCamera& camera);

/// Where the materials of one object's pieces are in SceneAssets::materials: the skin's, the
/// hollow walls' (the skin's material without the skin's texture) and the cut faces'.
struct PieceMaterials {
  int skin = 0, wall = 0, cut = 0;
};

/// Adds the skin and cut materials of the template named `name` to assets.materials, as
/// NAME_skin and NAME_cut (once per scene: a template seen before gets the same indices); a
/// default PbrMaterial is material 0, the scene's plain one.
PieceMaterials add_piece_materials(SceneAssets& assets, const std::string& name,
                                   const PbrMaterial& skin, const PbrMaterial& cut);

/// `piece` as an exportable mesh named `name`: `merged` is merge_parts of it (possibly
/// recoloured), its triangles those of the skin, the walls and the caps in turn; one primitive
/// per run of parts of one material (skin, walls, caps; none when all are material 0).
/// `uv`: #V texture coordinates (CapAtlas::uv and the skin's) or empty; `coarse_caps`: the
/// caps' coarse triangles (coarse_caps()) for the cap primitive, or empty.
AssetMesh piece_mesh(const ShadedMesh& merged, const Piece& piece, PieceMaterials materials,
                     const std::string& name, const std::vector<glm::dvec2>& uv = {},
                     const std::vector<glm::uvec3>& coarse_caps = {});

/// What `piece` is (its glTF node extras): template, variant seed, cut_label(cut), its cell,
/// the kinds of its parts and the volume of `merged` (merge_parts of it).
PieceInfo piece_info(const Piece& piece, const ShadedMesh& merged, const std::string& template_name,
                     uint64_t seed, const CutSpec& cut);

/// The caps of `piece` re-triangulated from their outlines (coarse_cap_triangles in the plane
/// frame of their section), over the vertex indices of merge_parts(piece).
std::vector<glm::uvec3> coarse_caps(const Piece& piece, const std::vector<CrossSection>& sections);

/// Bakes the caps of `pieces` (of one object, cut into `set`) into a texture added to
/// `assets`, adds a copy of material `materials.cut` textured with it, named "<object>_cut",
/// its roughness and translucency the means of the diffused material channels and, where
/// those vary, a material map "<object>_cut_material" (cap_atlas.h), and returns the object's
/// materials with it, and per piece the texture coordinates of its merge_parts vertices in `uv`.
/// Pieces without caps: `materials` and empty uv.
PieceMaterials add_cap_texture(SceneAssets& assets, const PieceSet& set,
                               const std::vector<const Piece*>& pieces, PieceMaterials materials,
                               const std::string& object, const ColourModulation* modulation,
                               double strength, const CapAtlasOptions& options,
                               std::vector<std::vector<glm::dvec2>>& uv);

/// Unwraps the skin part of each kept piece of `set` (unwrap_skin: adds vertices along the
/// seam and at the poles) and returns per kept piece its coordinates, or nothing for a piece
/// without skin.
std::vector<std::vector<glm::dvec2>> unwrap_skins(PieceSet& set, const std::vector<size_t>& kept);

/// Bakes the unwrapped skins of the kept pieces of `set` (one object whose DS skin is `skin`)
/// into a texture "<object>_skin" repeating in u (skin_texture.h), adds a copy of material
/// `materials.skin` textured with it and returns the object's materials with it as the skin's;
/// writes each kept piece's skin coordinates into the first entries of uv[q] (sized to the
/// piece's merge_parts vertices). No skins: `materials` unchanged.
PieceMaterials add_skin_texture(SceneAssets& assets, const DsSurface& skin, const PieceSet& set,
                                const std::vector<size_t>& kept,
                                const std::vector<std::vector<glm::dvec2>>& skin_uv,
                                PieceMaterials materials, const std::string& object,
                                const ColourModulation* modulation, double strength,
                                const SkinTextureOptions& options,
                                std::vector<std::vector<glm::dvec2>>& uv);

/// The outward normal of the piece's largest cap (by area), object frame; zero if it has none.
glm::dvec3 largest_cap_normal(const Piece& piece);

/// How cut_scene_object() cuts and colours one object.
struct ObjectCutOptions {
  CutSpec cut;                    ///< a cut that misses the object leaves it whole
  double keep = 1;                ///< the fraction of the pieces kept, (0, 1]; at least one
  uint64_t keep_seed = 0;         ///< which pieces are kept (a seeded choice)
  uint64_t modulation_seed = 0;   ///< Perlin colour modulation, in the object frame
  double perlin = 1;              ///< its strength, 0..10
  CapAtlasOptions atlas;          ///< with CapColours::Texture; texels_per_m > 0
};

/// One object cut into pieces, the kept ones ready for export, all in the object frame.
struct CutObject {
  PieceSet set;                    ///< every piece as cut (kept skins unwrapped when textured)
  std::vector<size_t> kept;        ///< indices into set.pieces, increasing
  std::vector<AssetMesh> meshes;   ///< per kept piece: as exported (materials, uv), named
                                   ///< OBJECT_pieceCELL
  std::vector<ShadedMesh> shapes;  ///< per kept piece: merge_parts as cut (layout, physics)
  std::vector<PieceInfo> infos;    ///< per kept piece: its glTF node extras
};

/// Cuts `variant` (built from seed `variant_seed`) as `cut` says with the backend of
/// options.diffusion, keeps a seeded share of the pieces and makes them exportable: with
/// CapColours::Texture the caps and swept skins baked into textures added to `assets` (named
/// after `object`), with materials derived from `materials` (add_piece_materials); colours
/// Perlin-modulated in the object frame. Adds its timings and counts to `st` (seconds_backend,
/// sections, diffuse, clip, bake; diffused_points, recut_objects, defective_pieces).
/// Deterministic, as build_scene.
/// @throws InternalError when options.diffusion is empty
CutObject cut_scene_object(SceneAssets& assets, const Variant& variant, uint64_t variant_seed,
                           const PieceMaterials& materials, const std::string& object,
                           const ObjectCutOptions& cut, const SceneBuildOptions& options,
                           SceneStats& st);

/// Builds the whole scene with `seed` (the file's seed unless the command line gives one).
/// Deterministic: the same scene, templates and seed give the same assets, whatever the
/// thread count of the diffusion backends.
/// A cut that misses an object leaves it whole.
/// @throws InputError when a template cannot be read or built
SceneAssets build_scene(const Scene& scene, uint64_t seed, const SceneBuildOptions& options,
                        SceneStats* stats = nullptr);

}  // namespace cutaway
