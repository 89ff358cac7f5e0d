// A labelled picture of one cut object's pieces, the tile of a contact sheet (`cutaway sheet`).
#pragma once

#include <string>

#include "assets/scene_assets.h"
#include "cut/object_cut.h"
#include "cut/piece_views.h"
#include "render/image/image.h"

namespace cutaway {

/// The pieces of `object` laid out in a grid (grid_piece_assets) as `view` shows them, over
/// `assets` (its materials and textures), with silhouette strokes of strength `silhouettes`
/// (0: none) as `cutaway piece --png` draws them, rendered `tile` pixels wide and 3/4 of that
/// high by the OpenGL preview, with the label `name` and `detail` (in grey) below
/// (labelled_tile).
/// @pre tile >= 64; `object` was cut into `assets` (cut_object)
/// @throws EnvironmentError when no OpenGL context can be created or rendering fails
Image piece_tile(SceneAssets assets, const CutObject& object, PieceView view, int tile,
                 double silhouettes, const std::string& name, const std::string& detail);

}  // namespace cutaway
