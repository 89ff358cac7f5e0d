// `cutaway sheet`: a contact sheet of cut objects, one labelled tile per template (the README's
// picture of the template library). Each object is cut into pieces as `cutaway piece` does; the
// pieces are then laid side by side on the ground, each turned so that its largest cut face
// looks up, and seen from the front and above, so that the inside shows.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "base/timer.h"
#include "cut/piece_views.h"
#include "diffusion/diffusion.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "render/image/contact_sheet.h"
#include "render/piece_tile.h"
#include "scene/scene.h"
#include "variation/variation.h"

namespace cutaway::cli {

namespace {

/// `cutaway sheet TEMPLATE[:CUT][@VIEW]... -o sheet.png [--cut SPEC] [--tile PX] [--columns N]`:
/// a contact sheet, one labelled tile per template, cut (by CUT or --cut: a `piece --cut` spec,
/// or `across`, one horizontal plane through the middle) with its pieces laid out cut face up
/// (VIEW up, the default) or standing with their cut faces toward the camera (VIEW upright);
/// with --seed S every template's variant of seed S (grains included).
struct SheetArgs {
  std::vector<std::string> items;  ///< "PATH.yaml[:CUT][@VIEW]"
  std::string output;              ///< .png
  std::string cut = "halves";      ///< the cut of items without their own
  int tile = 400;                  ///< tile width in pixels (height 3/4 of it plus the label)
  int columns = 0;                 ///< 0: about sqrt(4/3 * tiles)
  int cube = kDefaultCubeSize;
  StyleArgs style;    ///< --style, --silhouettes: strokes over the tiles
  int64_t seed = -1;  ///< >= 0: every template's variant of this seed (with its grains)
};

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
  const uint64_t seed = a.seed >= 0 ? static_cast<uint64_t>(a.seed) : 0;
  const Variant variant =
      a.seed >= 0 ? make_variant(tmpl, seed) : Variant{tmpl, build_model(tmpl), 0, 0.0};
  const DsModel& model = variant.model;
  if (item.across) cut.plane = mid_height_plane(model);
  SceneAssets assets;
  assets.name = tmpl.name;
  // Textured, so that skin patterns show per texel, not per vertex.
  const CutObject object =
      cut_for_view(assets, variant, cut, a.cube, common, 1.0, seed,
                   tmpl.name + ": cut '" + item.text + "'", CapColours::Texture);
  const Image tile = piece_tile(std::move(assets), object, item.view, a.tile,
                                stroke_strength(a.style), tmpl.name, item.text);
  spdlog::info("{} ({}): {} pieces, {:.1f} s", tmpl.name, item.text, object.set.pieces.size(),
               seconds_since(t0));
  return tile;
}

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
  const int columns = a.columns > 0 ? a.columns : sheet_columns(tiles.size());
  GridOptions grid;
  grid.margin = std::max(4, a.tile / 32);
  write_png(file, compose_grid(tiles, columns, grid));
  spdlog::info("wrote {} ({} tiles, {} columns)", a.output, tiles.size(), columns);
  return 0;
}

}  // namespace

Command add_sheet_command(CLI::App& app) {
  auto args = std::make_shared<SheetArgs>();
  CLI::App* sheet =
      app.add_subcommand("sheet", "contact sheet of cut templates, one labelled tile each (PNG)");
  sheet
      ->add_option("TEMPLATE", args->items,
                   "template files, each optionally with its own cut and view: "
                   "PATH.yaml[:CUT][@up|@upright]")
      ->required();
  sheet->add_option("-o,--output", args->output, "sheet to write (.png)")->required();
  sheet->add_option("--cut", args->cut,
                    "cut of templates without their own: as piece --cut, or across (one "
                    "horizontal plane at mid-height)");
  sheet->add_option("--tile", args->tile, "tile width in pixels")->check(number_rule(64, 2048));
  sheet->add_option("--columns", args->columns, "columns (0: about sqrt(4/3 tiles))")
      ->check(number_rule(0, 64));
  sheet->add_option("--cube", args->cube, "cube-map texels per face edge for PMVC")
      ->check(number_rule(2, 256));
  add_style_options(sheet, args->style, "over the tiles");
  sheet
      ->add_option("--seed", args->seed,
                   "cut every template's random variant of this seed (grains included) "
                   "instead of the template itself")
      ->check(seed_rule());
  return {sheet, [args](const Common& common, OutputSet& outputs) {
            return run_sheet(*args, common, outputs);
          }};
}

}  // namespace cutaway::cli
