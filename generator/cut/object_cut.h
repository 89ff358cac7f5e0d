// One object cut into pieces and made exportable (doc/architecture.md, Data flow, steps 3 to
// 5): the pieces of a seeded variant (pieces.h), a seeded share of them kept, their caps and
// swept skins baked into textures or left in vertex colours, their colours modulated by Perlin
// noise in the object frame (colour_modulation.h), each as an AssetMesh with the template's
// materials. The scene builder, asset batches, `cutaway piece` and `cutaway sheet` all cut
// objects with cut_object().
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "assets/scene_assets.h"
#include "base/outcome.h"
#include "diffusion/diffusion.h"
#include "material/cap_atlas.h"
#include "material/skin_texture.h"
#include "pieces/pieces.h"
#include "variation/variation.h"

namespace cutaway {

/// Makes the diffusion backend for one object's DS model (the CLI's --backend choice).
using DiffusionFactory = std::function<std::unique_ptr<DiffusionBackend>(const DsModel&)>;

/// Where cut faces take their colours from.
enum class CapColours {
  Texture,  ///< a baked texture per object (bake_cap_atlas); glTF caps use TEXCOORD_0
  Vertex,   ///< the vertex colours (COLOR_0), as before textures
};

/// Where the materials of one object's pieces are in SceneAssets::materials: the skin's, the
/// hollow walls' and stone imprints', the cut faces' and the whole stones' (the walls' and the
/// stones' are the skin's material without its texture until cut_object adds ones of their own,
/// from the roughness and translucency those parts show).
struct PieceMaterials {
  int skin = 0, wall = 0, cut = 0, stone = 0;
};

/// Adds the skin and cut materials of the template named `name` to assets.materials, as
/// NAME_skin and NAME_cut (once per scene: a template seen before gets the same indices); a
/// default PbrMaterial is material 0, the scene's plain one.
PieceMaterials add_piece_materials(SceneAssets& assets, const std::string& name,
                                   const PbrMaterial& skin, const PbrMaterial& cut);

/// How cut_object() cuts and colours one object.
struct ObjectCutOptions {
  CutSpec cut;
  /// A cut whose every plane misses the object: true keeps the object whole (one piece, as in
  /// scenes and batches); false makes cut_object() return the reason instead.
  bool whole_when_missed = true;
  double keep = 1;               ///< the fraction of the pieces kept, (0, 1]; at least one
  uint64_t keep_seed = 0;        ///< which pieces are kept (a seeded choice)
  uint64_t modulation_seed = 0;  ///< Perlin colour modulation, in the object frame
  double perlin = 1;             ///< its strength, 0..10
  CapSampling sampling = CapSampling::Adaptive;  ///< which cap points are diffused
  CapColours cap_colours = CapColours::Texture;
  CapAtlasOptions atlas;    ///< with CapColours::Texture; texels_per_m > 0
  SkinTextureOptions skin;  ///< with CapColours::Texture: the swept skin's texture
};

/// Counts and timings (wall seconds) of cut_object() calls, added up.
struct ObjectCutStats {
  DiffusedPoints diffused;      ///< PMVC evaluations of the caps
  int recut_objects = 0;        ///< objects whose cut was redone with nudged planes
  size_t defective_pieces = 0;  ///< pieces left with a manifold defect after every attempt
  double seconds_sections = 0;  ///< cap cross-sections (triangulation + PMVC)
  double seconds_diffuse = 0;   ///< of which PMVC
  double seconds_clip = 0;      ///< clipping the skin and walls, stitching
  double seconds_bake = 0;      ///< baking cap and skin textures
};

/// The kept pieces of one object ready for export, all in the object frame: what scenes,
/// batches and the piece views use, and what the cut cache stores (cut_cache.h).
struct CutPieces {
  std::string backend;                  ///< the diffusion backend's name (DiffusionBackend::name)
  size_t pieces_cut = 0;                ///< pieces the cut made, before `keep`
  std::vector<AssetMesh> meshes;        ///< per kept piece: as exported (materials, uv, modulated
                                        ///< colours), named OBJECT_pieceCELL
  std::vector<ShadedMesh> shapes;       ///< per kept piece: merge_parts as cut, before its skin
                                        ///< was unwrapped (layout, physics, bounds; colours unused)
  std::vector<PieceInfo> infos;         ///< per kept piece: its glTF node extras
  std::vector<glm::dvec3> cap_normals;  ///< per kept piece: largest_cap_normal
  std::vector<int> cut_faces;           ///< per kept piece: cut_faces
};

/// One object cut into pieces: the kept ones ready for export, and the whole cut.
struct CutObject : CutPieces {
  /// The cut: its kept pieces (skins unwrapped when textured), their sections and counts.
  PieceSet set;
};

/// Cuts `variant` (built from seed `variant_seed`) as options.cut says, its caps coloured by
/// `diffusion` (a backend built for variant.model; one backend serves any number of cuts of
/// it), keeps a seeded share of the pieces and makes them exportable: with
/// CapColours::Texture the caps and swept skins baked into textures added to `assets` (named
/// after `object`), with materials derived from `materials` (add_piece_materials); colours
/// Perlin-modulated in the object frame. Adds its timings and counts to `stats`.
/// Deterministic: the same variant and options give the same pieces, whatever the thread count
/// of the backend.
/// @return the reason when every plane misses the object and !options.whole_when_missed
Outcome<CutObject> cut_object(SceneAssets& assets, const Variant& variant, uint64_t variant_seed,
                              const PieceMaterials& materials, const std::string& object,
                              const DiffusionBackend& diffusion, const ObjectCutOptions& options,
                              ObjectCutStats& stats);

/// The caps of `piece` re-triangulated from their outlines (coarse_cap_triangles in the plane
/// frame of their section), over the vertex indices of merge_parts(piece).
std::vector<glm::uvec3> coarse_caps(const Piece& piece, const std::vector<CrossSection>& sections);

/// The outward normal of the piece's largest cap (by area), object frame; zero if it has none.
glm::dvec3 largest_cap_normal(const Piece& piece);

/// The number of distinct cut planes among the piece's caps (normals apart by over 2.5 degrees).
int cut_faces(const Piece& piece);

}  // namespace cutaway
