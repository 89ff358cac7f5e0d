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

#include "colour_modulation.h"
#include "commands.h"
#include "contact_sheet.h"
#include "cut_spec.h"
#include "diffusion_backends.h"
#include "model_builder.h"
#include "pieces.h"
#include "scene_builder.h"
#include "scene_preview.h"
#include "silhouettes.h"
#include "template_parser.h"
#include "text_label.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// How a tile shows its pieces.
enum class View {
  Up,       ///< each piece lying with its largest cut face up, seen from 55 degrees above
  Upright,  ///< each piece standing as in the object, turned about its axis so that its
            ///< largest cut face looks at the camera, seen from 25 degrees above
};

/// One tile's template, cut and view: "PATH.yaml[:CUT][@VIEW]" (the cut after the first ':'
/// that follows ".yaml"; VIEW up or upright).
struct SheetItem {
  std::string template_path, cut;
  View view = View::Up;
};

SheetItem parse_item(std::string text, const std::string& default_cut) {
  SheetItem item;
  const size_t at = text.rfind('@');
  if (at != std::string::npos && text.find(".yaml", at) == std::string::npos) {
    const std::string view = text.substr(at + 1);
    if (view == "upright") item.view = View::Upright;
    else if (view != "up")
      throw UsageError("'" + text + "': the view after @ must be up or upright");
    text.resize(at);
  }
  const size_t yaml = text.find(".yaml:");
  item.template_path = yaml == std::string::npos ? text : text.substr(0, yaml + 5);
  item.cut = yaml == std::string::npos ? default_cut : text.substr(yaml + 6);
  return item;
}

/// The axis-aligned bounds of `mesh` turned by `rotation`.
void rotated_bounds(const ShadedMesh& mesh, const glm::dquat& rotation, glm::dvec3& lo,
                    glm::dvec3& hi) {
  lo = glm::dvec3(std::numeric_limits<double>::max());
  hi = -lo;
  for (const glm::dvec3& p : mesh.position) {
    const glm::dvec3 q = rotation * p;
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
}

/// The turn that shows a piece whose largest cap has the outward `normal` (zero: no cap, no
/// turn) as `view` asks: the normal up (Up), or turned about +Y toward +Z (Upright).
glm::dquat view_rotation(const glm::dvec3& normal, View view) {
  const glm::dquat none(1, 0, 0, 0);
  if (glm::length(normal) < 0.5) return none;
  if (view == View::Up) return glm::rotation(glm::normalize(normal), glm::dvec3(0, 1, 0));
  const glm::dvec2 flat(normal.x, normal.z);
  if (glm::length(flat) < 1e-3) return none;  // a horizontal cap: no turn shows it better
  return glm::angleAxis(std::atan2(normal.x, normal.z) * -1.0, glm::dvec3(0, 1, 0));
}

/// The pieces of one object as a little scene: each piece turned as `view` asks (a piece
/// without caps keeps its pose), standing on y = 0, in a grid of cells of the largest piece's
/// footprint whose column count makes the view closest to the tile's aspect; seen from the
/// front (+Z) and above, with the studio lights.
SceneAssets sheet_assets(const PieceSet& set, const std::string& name, View view, int width,
                         int height) {
  const double el = glm::radians(view == View::Up ? 55.0 : 25.0);
  const glm::dvec3 to_camera(0, std::sin(el), std::cos(el));
  SceneAssets assets;
  assets.name = name;
  assets.width = width;
  assets.height = height;
  assets.background = {1, 1, 1};
  const size_t n = set.pieces.size();
  std::vector<glm::dquat> rotation(n);
  std::vector<glm::dvec3> lo(n), hi(n);
  glm::dvec3 cell(0.0);
  for (size_t k = 0; k < n; ++k) {
    const Piece& piece = set.pieces[k];
    rotation[k] = view_rotation(largest_cap_normal(piece), view);
    const ShadedMesh mesh = merge_parts(piece);
    rotated_bounds(mesh, rotation[k], lo[k], hi[k]);
    cell = glm::max(cell, hi[k] - lo[k]);
    const std::string piece_name = name + "_piece" + std::to_string(piece.cell);
    assets.meshes.push_back(asset_mesh(mesh, piece_name));
  }
  // Columns: the grid whose projected width / height is nearest the image's aspect. Rows are
  // far enough apart that a front row hides at most the bottom of the row behind it.
  const double gap = 0.12 * std::max(cell.x, cell.z);
  const double pitch = std::max(cell.z + gap, 0.8 * cell.y / std::tan(el));
  const double aspect = static_cast<double>(width) / height;
  int columns = 1;
  double best = std::numeric_limits<double>::max();
  for (int c = 1; c <= static_cast<int>(n); ++c) {
    const int rows = static_cast<int>((n + c - 1) / c);
    const double w = c * cell.x + (c - 1) * gap;
    const double d = cell.z + (rows - 1) * pitch;
    const double h = d * std::sin(el) + cell.y * std::cos(el);
    const double miss = std::abs(std::log(w / h / aspect));
    if (miss < best - 1e-9) best = miss, columns = c;
  }
  const int rows = static_cast<int>((n + columns - 1) / columns);
  glm::dvec3 all_lo(std::numeric_limits<double>::max()), all_hi(-all_lo);
  for (size_t k = 0; k < n; ++k) {
    const int col = static_cast<int>(k) % columns, row = static_cast<int>(k) / columns;
    // The cell's centre on the ground; rows run from the back (-Z) to the front (+Z).
    const glm::dvec3 centre((col - 0.5 * (columns - 1)) * (cell.x + gap), 0,
                            (row - 0.5 * (rows - 1)) * pitch);
    const glm::dvec3 mid = 0.5 * (lo[k] + hi[k]);
    const glm::dvec3 offset = centre - glm::dvec3(mid.x, lo[k].y, mid.z);
    all_lo = glm::min(all_lo, lo[k] + offset);
    all_hi = glm::max(all_hi, hi[k] + offset);
    assets.instances.push_back({assets.meshes[k].name, static_cast<int>(k), rotation[k], offset});
  }
  assets.camera = frame_box(all_lo, all_hi, to_camera, 30, aspect);
  assets.lights = studio_lights(assets.camera);
  return assets;
}

/// One tile's template, loaded, and its cut, parsed and checked.
struct LoadedItem {
  std::string text;  ///< the cut as given
  View view = View::Up;
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
  try {
    out.cut = parse_cut_spec(item.cut, out.tmpl.metres_per_unit);
  } catch (const std::invalid_argument& e) {
    throw UsageError(item.template_path + ": cut '" + item.cut + "': " + e.what());
  }
  const long long estimate = estimate_piece_count(out.cut, template_extents(out.tmpl));
  if (estimate > kMaxPiecesPerCut)
    throw UsageError(item.template_path + ": cut '" + item.cut + "' would make about " +
                     std::to_string(estimate) + " pieces (at most " +
                     std::to_string(kMaxPiecesPerCut) + ")");
  return out;
}

/// One labelled tile: the pieces of one cut object, the label below them.
Image sheet_tile(const LoadedItem& item, const SheetArgs& a, const Common& common) {
  const auto t0 = Clock::now();
  const Template& tmpl = item.tmpl;
  CutSpec cut = item.cut;
  const DsModel model = build_model(tmpl);
  if (item.across) cut.plane = {{0, 0.5 * (model.bbox_min.y + model.bbox_max.y), 0}, {0, 1, 0}};
  const auto diffusion =
      make_diffusion(model, {a.cube, common.threads}, parse_diffusion_choice(common.backend));
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  PieceSet set;
  try {
    set = cut_pieces(model, cut, *diffusion, options);
  } catch (const std::domain_error& e) {
    throw UsageError(tmpl.name + ": cut '" + item.text + "': " + e.what());
  }
  for (Piece& p : set.pieces)
    for (PiecePart& part : p.parts) modulate_colours(part.mesh, tmpl.npr, 1.0, 0);
  const int picture_h = a.tile * 3 / 4;
  const SceneAssets assets = sheet_assets(set, tmpl.name, item.view, a.tile, picture_h);
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
  const int scale = std::max(1, a.tile / 160);
  const LabelSize name_size = label_size(tmpl.name, scale);
  const std::string cut_text = "  " + item.text;
  const LabelSize cut_size = label_size(cut_text, scale);
  const int strip = name_size.height + 4 * scale;
  Image tile;
  tile.width = a.tile;
  tile.height = picture_h + strip;
  tile.rgba.assign(static_cast<size_t>(tile.width) * tile.height * 4, 255);
  std::copy(picture.rgba.begin(), picture.rgba.end(), tile.rgba.begin());
  const int x = (tile.width - name_size.width - cut_size.width) / 2;
  draw_label(tile, tmpl.name, x, picture_h + scale, scale, glm::dvec3(0.0));
  draw_label(tile, cut_text, x + name_size.width, picture_h + scale, scale, glm::dvec3(0.5));
  spdlog::info("{} ({}): {} pieces, {:.1f} s", tmpl.name, item.text, set.pieces.size(),
               std::chrono::duration<double>(Clock::now() - t0).count());
  return tile;
}

}  // namespace

int run_sheet(const SheetArgs& a, const Common& common) {
  if (a.items.empty()) throw UsageError("give at least one template");
  require_extension("-o", a.output, ".png");
  if (a.tile < 64 || a.tile > 2048) throw UsageError("--tile must be in 64..2048");
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
  const std::filesystem::path parent = std::filesystem::path(a.output).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  write_png(a.output, compose_grid(tiles, columns, grid));
  spdlog::info("wrote {} ({} tiles, {} columns)", a.output, tiles.size(), columns);
  return 0;
}

}  // namespace cutaway::cli
