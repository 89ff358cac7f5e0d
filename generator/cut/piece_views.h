// Pictures of the pieces of one object (`cutaway piece --png`, `cutaway sheet`): the pieces
// as a small SceneAssets, either pulled apart from the object's centre or laid side by side on
// the ground with their cut faces showing; and the whole object in its own frame (the asset an
// interior volume goes with).
#pragma once

#include <string>

#include "assets/scene_assets.h"
#include "cut/object_cut.h"

namespace cutaway {

/// The kept pieces of one object (cut_object) for `cutaway piece`: each pulled away from the
/// object's centre along the direction d to its own centroid by explode * (2 |d| + size / 4)
/// (size: the object's bounding-box diagonal), so slices spread evenly, framed from the
/// front-right 50 degrees up, studio lights, white background. `assets` holds the materials
/// and textures cut_object() added and its name; the pieces' meshes and instances are added.
SceneAssets piece_assets(SceneAssets assets, const CutPieces& object, double explode, int width,
                         int height);

/// `variant` uncut as an asset in its object frame (metres, +Y up, where its interior volume
/// lies): one mesh, its skin baked into a texture with the skin's patterns and the Perlin
/// modulation of strength `perlin` and `seed` (cut_object), the template's skin material, a
/// front camera and studio lights (for those who render it).
SceneAssets whole_object_assets(const Variant& variant, const DiffusionBackend& diffusion,
                                double perlin, uint64_t seed);

/// How grid_piece_assets() turns each piece.
enum class PieceView {
  Up,       ///< each piece lying with its largest cut face up, seen from 55 degrees above
  Upright,  ///< each piece standing as in the object, turned about its axis so that its
            ///< largest cut face looks at the camera, seen from 25 degrees above
};

/// The kept pieces of one object (cut_object) laid out as a little scene: each piece turned as
/// `view` asks (a piece without caps keeps its pose), standing on y = 0, in a grid of cells of
/// the largest piece's footprint whose column count makes the view closest to the tile's
/// aspect; seen from the front (+Z) and above, with the studio lights, white background.
/// `assets` as for piece_assets().
SceneAssets grid_piece_assets(SceneAssets assets, const CutPieces& object, PieceView view,
                              int width, int height);

}  // namespace cutaway
