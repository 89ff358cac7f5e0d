#include "render/piece_tile.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "npr/silhouettes.h"
#include "render/image/contact_sheet.h"
#include "render/scene_preview.h"

namespace cutaway {

Image piece_tile(SceneAssets assets, const CutObject& object, PieceView view, int tile,
                 double silhouettes, const std::string& name, const std::string& detail) {
  assets = grid_piece_assets(std::move(assets), object, view, tile, tile * 3 / 4);
  std::vector<Stroke> strokes;
  if (silhouettes > 0) {
    StrokeOptions so;
    so.strength = silhouettes;
    strokes = extract_strokes(assets, so);
  }
  ScenePreviewOptions preview;
  preview.strokes = &strokes;
  return labelled_tile(render_scene_preview(assets, preview), name, detail,
                       std::max(1, tile / 160));
}

}  // namespace cutaway
