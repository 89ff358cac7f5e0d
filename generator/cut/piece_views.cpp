#define GLM_ENABLE_EXPERIMENTAL
#include "cut/piece_views.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtx/quaternion.hpp>

#include "assets/asset_camera.h"

namespace cutaway {

namespace {

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
glm::dquat view_rotation(const glm::dvec3& normal, PieceView view) {
  const glm::dquat none(1, 0, 0, 0);
  if (glm::length(normal) < 0.5) return none;
  if (view == PieceView::Up) return glm::rotation(glm::normalize(normal), glm::dvec3(0, 1, 0));
  const glm::dvec2 flat(normal.x, normal.z);
  if (glm::length(flat) < 1e-3) return none;  // a horizontal cap: no turn shows it better
  return glm::angleAxis(std::atan2(normal.x, normal.z) * -1.0, glm::dvec3(0, 1, 0));
}

}  // namespace

SceneAssets piece_assets(SceneAssets assets, const CutPieces& object, double explode, int width,
                         int height) {
  assets.width = width;
  assets.height = height;
  assets.background = {1, 1, 1};
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-lo);
  for (const ShadedMesh& shape : object.shapes) {
    for (const glm::dvec3& p : shape.position) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double size = glm::distance(lo, hi);
  glm::dvec3 elo(std::numeric_limits<double>::max()), ehi(-elo);
  for (size_t k = 0; k < object.shapes.size(); ++k) {
    const ShadedMesh& shape = object.shapes[k];
    glm::dvec3 c(0.0);
    for (const glm::dvec3& p : shape.position) c += p;
    c /= static_cast<double>(shape.position.size());
    const glm::dvec3 d = c - centre;
    // Apart by a share of the piece's own offset (slices spread evenly) plus a fixed gap.
    const glm::dvec3 offset = glm::length(d) > 1e-9 * size
                                  ? explode * (2.0 * d + 0.25 * size * glm::normalize(d))
                                  : glm::dvec3(0.0);
    for (const glm::dvec3& p : shape.position) {
      elo = glm::min(elo, p + offset);
      ehi = glm::max(ehi, p + offset);
    }
    assets.instances.push_back({object.meshes[k].name,
                                static_cast<int>(assets.meshes.size()),
                                {1, 0, 0, 0},
                                offset,
                                object.infos[k]});
    assets.meshes.push_back(object.meshes[k]);
  }
  const double az = glm::radians(20.0), el = glm::radians(50.0);
  assets.camera =
      frame_box(elo, ehi, {std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)},
                30, static_cast<double>(width) / height);
  light_like_studio(assets);
  return assets;
}

SceneAssets grid_piece_assets(SceneAssets assets, const CutPieces& object, PieceView view,
                              int width, int height) {
  const double el = glm::radians(view == PieceView::Up ? 55.0 : 25.0);
  const glm::dvec3 to_camera(0, std::sin(el), std::cos(el));
  assets.width = width;
  assets.height = height;
  assets.background = {1, 1, 1};
  const size_t n = object.meshes.size(), first_mesh = assets.meshes.size();
  std::vector<glm::dquat> rotation(n);
  std::vector<glm::dvec3> lo(n), hi(n);
  glm::dvec3 cell(0.0);
  for (size_t k = 0; k < n; ++k) {
    rotation[k] = view_rotation(object.cap_normals[k], view);
    rotated_bounds(object.shapes[k], rotation[k], lo[k], hi[k]);
    cell = glm::max(cell, hi[k] - lo[k]);
    assets.meshes.push_back(object.meshes[k]);
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
    assets.instances.push_back(
        {object.meshes[k].name, static_cast<int>(first_mesh + k), rotation[k], offset, {}});
  }
  assets.camera = frame_box(all_lo, all_hi, to_camera, 30, aspect);
  light_like_studio(assets);
  return assets;
}

SceneAssets whole_object_assets(const Variant& variant, const DiffusionBackend& diffusion,
                                double perlin, uint64_t seed) {
  SceneAssets assets;
  assets.name = variant.tmpl.name;
  const PieceMaterials materials = add_piece_materials(
      assets, variant.tmpl.name, variant.tmpl.skin_material, variant.tmpl.cut_material);
  ObjectCutOptions options;
  options.cut = CutSpec{};  // CutType::Whole
  options.modulation_seed = seed;
  options.perlin = perlin;
  options.cap_colours = CapColours::Texture;
  ObjectCutStats stats;
  const Outcome<CutObject> object = cut_object(
      assets, variant, seed, materials, asset_name(variant.tmpl.name), diffusion, options, stats);
  CUTAWAY_CHECK(object.has_value());  // a whole object is never missed
  return piece_assets(std::move(assets), *object, 0.0, 800, 600);
}

}  // namespace cutaway
