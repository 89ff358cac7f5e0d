// Contact sheets (render/image/contact_sheet.h).
#include "render/image/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "base/error.h"
#include "render/image/text_label.h"
#include "render/section_preview.h"

namespace cutaway {
namespace {

constexpr int kMaxSheetSide = 16384;

void fail(const std::string& what) { throw InternalError("contact sheet: " + what); }

/// An opaque image of w x h pixels filled with `srgb` (0..1).
Image filled(int w, int h, const glm::dvec3& srgb) {
  Image im;
  im.width = w;
  im.height = h;
  im.rgba.resize(static_cast<size_t>(w) * h * 4);
  uint8_t px[4] = {0, 0, 0, 255};
  for (int c = 0; c < 3; ++c)
    px[c] = static_cast<uint8_t>(std::lround(std::clamp(srgb[c], 0.0, 1.0) * 255.0));
  for (size_t i = 0; i < im.rgba.size(); i += 4) std::copy(px, px + 4, im.rgba.begin() + i);
  return im;
}

/// Copies `tile` into `sheet` with its top-left pixel at (x, y); it must fit.
void blit(Image& sheet, const Image& tile, int x, int y) {
  const size_t row_bytes = static_cast<size_t>(tile.width) * 4;
  for (int r = 0; r < tile.height; ++r) {
    const auto src = tile.rgba.begin() + static_cast<ptrdiff_t>(r * row_bytes);
    const size_t dst = (static_cast<size_t>(y + r) * sheet.width + x) * 4;
    std::copy(src, src + static_cast<ptrdiff_t>(row_bytes), sheet.rgba.begin() + dst);
  }
}

}  // namespace

int sheet_columns(size_t tiles) {
  return static_cast<int>(std::ceil(std::sqrt(4.0 / 3.0 * static_cast<double>(tiles))));
}

Image compose_grid(const std::vector<Image>& tiles, int columns, const GridOptions& options) {
  if (tiles.empty()) fail("no tiles");
  if (columns < 1) fail("columns must be >= 1, got " + std::to_string(columns));
  if (options.margin < 0) fail("margin must be >= 0, got " + std::to_string(options.margin));
  int cell_w = 0, cell_h = 0;
  for (size_t i = 0; i < tiles.size(); ++i) {
    const Image& t = tiles[i];
    if (t.width <= 0 || t.height <= 0 ||
        t.rgba.size() != static_cast<size_t>(t.width) * t.height * 4)
      fail("tile " + std::to_string(i) + " is malformed (" + std::to_string(t.width) + " x " +
           std::to_string(t.height) + ", " + std::to_string(t.rgba.size()) + " bytes)");
    cell_w = std::max(cell_w, t.width);
    cell_h = std::max(cell_h, t.height);
  }
  const int64_t n = static_cast<int64_t>(tiles.size());
  const int64_t cols = std::min<int64_t>(columns, n);
  const int64_t rows = (n + cols - 1) / cols;
  const int64_t w = cols * cell_w + (cols + 1) * int64_t{options.margin};
  const int64_t h = rows * cell_h + (rows + 1) * int64_t{options.margin};
  if (w > kMaxSheetSide || h > kMaxSheetSide)
    fail("the sheet would be " + std::to_string(w) + " x " + std::to_string(h) +
         " pixels (at most " + std::to_string(kMaxSheetSide) + " a side)");
  Image sheet = filled(static_cast<int>(w), static_cast<int>(h), options.background_srgb);
  for (int64_t i = 0; i < n; ++i) {
    const Image& t = tiles[static_cast<size_t>(i)];
    const int64_t cx = options.margin + (i % cols) * (cell_w + options.margin);
    const int64_t cy = options.margin + (i / cols) * (cell_h + options.margin);
    blit(sheet, t, static_cast<int>(cx + (cell_w - t.width + 1) / 2),
         static_cast<int>(cy + (cell_h - t.height + 1) / 2));
  }
  return sheet;
}

std::vector<Image> render_section_tiles(const std::vector<CrossSection>& sections,
                                        const SectionTileOptions& options) {
  if (sections.empty()) fail("no sections");
  if (options.tile_px < 16 || options.tile_px > 4096)
    fail("tile_px must be in 16..4096, got " + std::to_string(options.tile_px));
  // Each section's extent in its own (u, v) frame, as render_section_preview() fits it.
  std::vector<glm::dvec2> extent(sections.size());
  double largest = 0;
  for (size_t i = 0; i < sections.size(); ++i) {
    const CrossSection& s = sections[i];
    if (s.position.empty()) fail("section " + std::to_string(i) + " has no vertices");
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const glm::dvec3& p : s.position) {
      const glm::dvec3 d = p - s.plane.point;
      const glm::dvec2 q(glm::dot(d, s.u_axis), glm::dot(d, s.v_axis));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    extent[i] = hi - lo;
    largest = std::max({largest, extent[i].x, extent[i].y});
  }
  if (!(largest > 0 && std::isfinite(largest))) fail("the sections have no extent");
  const double pixels_per_m = options.tile_px / largest;
  std::vector<Image> tiles;
  tiles.reserve(sections.size());
  for (size_t i = 0; i < sections.size(); ++i) {
    SectionPreviewOptions o;
    o.width =
        std::clamp(static_cast<int>(std::lround(extent[i].x * pixels_per_m)), 1, options.tile_px);
    o.height =
        std::clamp(static_cast<int>(std::lround(extent[i].y * pixels_per_m)), 1, options.tile_px);
    o.margin = 0;
    o.samples = options.samples;
    o.background_srgb = options.background_srgb;
    const Image picture = render_section_preview(sections[i], o);
    Image tile = filled(options.tile_px, options.tile_px, options.background_srgb);
    blit(tile, picture, (options.tile_px - picture.width) / 2,
         (options.tile_px - picture.height) / 2);
    tiles.push_back(std::move(tile));
  }
  return tiles;
}

Image labelled_tile(const Image& picture, const std::string& name, const std::string& detail,
                    int scale) {
  if (picture.width < 1 || picture.height < 1 ||
      picture.rgba.size() != static_cast<size_t>(picture.width) * picture.height * 4 || scale < 1)
    throw InternalError("labelled_tile: a malformed picture or a scale below 1");
  const LabelSize name_size = label_size(name, scale);
  const std::string detail_text = "  " + detail;
  const LabelSize detail_size = label_size(detail_text, scale);
  const int strip = name_size.height + 4 * scale;
  Image tile;
  tile.width = picture.width;
  tile.height = picture.height + strip;
  tile.rgba.assign(static_cast<size_t>(tile.width) * tile.height * 4, 255);
  std::copy(picture.rgba.begin(), picture.rgba.end(), tile.rgba.begin());
  const int x = (tile.width - name_size.width - detail_size.width) / 2;
  draw_label(tile, name, x, picture.height + scale, scale, glm::dvec3(0.0));
  draw_label(tile, detail_text, x + name_size.width, picture.height + scale, scale,
             glm::dvec3(0.5));
  return tile;
}

Image section_sheet(std::vector<Outcome<CrossSection>> sections, const SectionTileOptions& options,
                    int columns) {
  std::vector<CrossSection> present;
  for (Outcome<CrossSection>& s : sections)
    if (s) present.push_back(std::move(*s));
  std::vector<Image> drawn = render_section_tiles(present, options);
  std::vector<Image> tiles;
  size_t next = 0;
  for (const Outcome<CrossSection>& s : sections)
    tiles.push_back(s ? std::move(drawn[next++])
                      : filled(options.tile_px, options.tile_px, options.background_srgb));
  if (columns <= 0)
    columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles.size()))));
  return compose_grid(tiles, columns);
}

}  // namespace cutaway
