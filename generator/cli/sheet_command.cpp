// `cutaway sheet`: a contact sheet of cut objects, one labelled tile per template (the README's
// picture of the template library). Each object is cut into pieces as `cutaway piece` does; the
// pieces are then laid side by side on the ground, each turned so that its largest cut face
// looks up, and seen from the front and above, so that the inside shows.
#define GLM_ENABLE_EXPERIMENTAL
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <glm/gtx/quaternion.hpp>
#include <spdlog/spdlog.h>

#include "base/timer.h"
#include "cli/commands.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "npr/silhouettes.h"
#include "render/image/contact_sheet.h"
#include "render/scene_preview.h"
#include "scene/piece_views.h"
#include "scene/scene.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// One tile's template, cut and view: "PATH.yaml[:CUT][@VIEW]" (the cut after the first ':'
/// that follows ".yaml"; VIEW up or upright).
struct SheetItem {
  std::string template_path, cut;
  PieceView view = PieceView::Up;
};

SheetItem parse_item(std::string text, const std::string& default_cut) {
  SheetItem item;
  const size_t at = text.rfind('@');
  if (at != std::string::npos && text.find(".yaml", at) == std::string::npos) {
    const std::string view = text.substr(at + 1);
    if (view == "upright") item.view = PieceView::Upright;
    else if (view != "up")
      throw UsageError("'" + text + "': the view after @ must be up or upright");
    text.resize(at);
  }
  const size_t yaml = text.find(".yaml:");
  item.template_path = yaml == std::string::npos ? text : text.substr(0, yaml + 5);
  item.cut = yaml == std::string::npos ? default_cut : text.substr(yaml + 6);
  return item;
}

/// One tile's template, loaded, and its cut, parsed and checked.
struct LoadedItem {
  std::string text;  ///< the cut as given
  PieceView view = PieceView::Up;
  Template tmpl;
  CutSpec cut;
  bool across = false;  ///< "across": one horizontal plane through the model's mid-height
};

LoadedItem load_item(const SheetItem& item) {
  LoadedItem out{item.cut, item.view, load_template(item.template_path), {}};
  if (item.cut == "across") {  // the plane is placed once the model's height is known
    out.cut.type = CutType::Plane;
    out.across = true;
    return out;
  }
  out.cut = checked_cut(out.tmpl, item.cut, item.template_path + ": cut '" + item.cut + "'");
  return out;
}

/// One labelled tile: the pieces of one cut object, the label below them.
Image sheet_tile(const LoadedItem& item, const SheetArgs& a, const Common& common) {
  const auto t0 = Clock::now();
  const Template& tmpl = item.tmpl;
  CutSpec cut = item.cut;
  const Variant variant{tmpl, build_model(tmpl)};
  const DsModel& model = variant.model;
  if (item.across) cut.plane = mid_height_plane(model);
  SceneAssets assets;
  assets.name = tmpl.name;
  const CutObject object = cut_for_view(assets, variant, cut, a.cube, common, 1.0, 0,
                                        tmpl.name + ": cut '" + item.text + "'");
  const int picture_h = a.tile * 3 / 4;
  assets = grid_piece_assets(std::move(assets), object, item.view, a.tile, picture_h);
  std::vector<Stroke> strokes;  // silhouettes as `cutaway piece --png` draws them
  if (a.silhouettes > 0) {
    StrokeOptions so;
    so.strength = a.silhouettes;
    strokes = extract_strokes(assets, so);
  }
  ScenePreviewOptions preview;
  preview.strokes = &strokes;
  const Image picture = render_scene_preview(assets, preview);
  // The label strip below the picture: the name, and the cut in grey.
  const Image tile = labelled_tile(picture, tmpl.name, item.text, std::max(1, a.tile / 160));
  spdlog::info("{} ({}): {} pieces, {:.1f} s", tmpl.name, item.text, object.set.pieces.size(),
               seconds_since(t0));
  return tile;
}

}  // namespace

int run_sheet(const SheetArgs& a, const Common& common, OutputSet& outputs) {
  if (a.items.empty()) throw UsageError("give at least one template");
  require_extension("-o", a.output, ".png");
  if (a.tile < 64 || a.tile > 2048) throw UsageError("--tile must be in 64..2048");
  // The sheet's pixels, at most: one tile-wide square per template.
  const long long pixels = static_cast<long long>(a.items.size()) * a.tile * a.tile;
  if (pixels > kMaxRenderPixels)
    throw UsageError("--tile " + std::to_string(a.tile) + " with " +
                     std::to_string(a.items.size()) + " templates makes a sheet of up to " +
                     std::to_string(pixels) + " pixels (at most " +
                     std::to_string(kMaxRenderPixels) + "): a smaller --tile");
  const std::filesystem::path file = outputs.add("-o", a.output);
  // Every template and cut is checked before anything is rendered.
  std::vector<LoadedItem> items;
  for (const std::string& text : a.items) items.push_back(load_item(parse_item(text, a.cut)));
  std::vector<Image> tiles;
  for (const LoadedItem& item : items) tiles.push_back(sheet_tile(item, a, common));
  const int columns =
      a.columns > 0 ? a.columns
                    : static_cast<int>(std::ceil(std::sqrt(4.0 / 3.0 * static_cast<double>(tiles.size()))));
  GridOptions grid;
  grid.margin = std::max(4, a.tile / 32);
  write_png(file, compose_grid(tiles, columns, grid));
  spdlog::info("wrote {} ({} tiles, {} columns)", a.output, tiles.size(), columns);
  return 0;
}

}  // namespace cutaway::cli
