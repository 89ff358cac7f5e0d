// Contact sheets: many pictures laid out in one grid image, like the variants of the paper's
// Fig. 8 (Takayama et al. 2010, §4.2), and the cross-sections of many models drawn at one
// common scale so that their size differences show.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "base/outcome.h"
#include "render/image/image.h"
#include "section/cross_section.h"

namespace cutaway {

/// The columns of a sheet of `tiles` tiles (>= 1) in about 4:3: ceil(sqrt(4/3 tiles)).
int sheet_columns(size_t tiles);

/// How compose_grid() lays the tiles out.
struct GridOptions {
  int margin = 16;  ///< empty pixels around the sheet and between neighbouring cells, >= 0
  glm::dvec3 background_srgb{1, 1, 1};  ///< opaque background of the sheet, sRGB 0..1
};

/// Lays `tiles` out in a grid of `columns` columns, row by row (tile i in row i / columns,
/// column i % columns), top left first. Every cell has the size of the largest tile (the
/// largest width by the largest height); a smaller tile is centred in its cell (an odd
/// remainder goes right / down), and everything not covered by a tile is the background.
/// Cells are `options.margin` pixels apart and the same margin surrounds the grid, so the
/// sheet is columns * cell_w + (columns + 1) * margin wide and rows * cell_h + (rows + 1) *
/// margin high, rows = ceil(tiles / columns). Tile pixels are copied unchanged (alpha
/// included); the background is opaque. The result depends on nothing but the arguments.
/// @param tiles   at least one; each with width, height > 0 and rgba.size() == w * h * 4
/// @param columns >= 1; more columns than tiles leaves the extra columns out (the sheet is
///                min(columns, tiles) cells wide)
/// @throws InternalError when tiles is empty or a tile is malformed, columns < 1,
///         margin < 0, or the sheet would exceed 16384 pixels on a side
Image compose_grid(const std::vector<Image>& tiles, int columns, const GridOptions& options = {});

/// `picture` with a white label strip below it: `name` in black followed by two spaces and
/// `detail` in grey, centred, in the bitmap font of text_label.h at `scale` (>= 1) times its
/// size. The tile is as wide as the picture and the strip as high as the text plus 4 * scale.
/// @throws InternalError when the picture is malformed or scale < 1
Image labelled_tile(const Image& picture, const std::string& name, const std::string& detail,
                    int scale);

/// How render_section_tiles() draws.
struct SectionTileOptions {
  int tile_px = 256;  ///< pixels the largest extent (width or height, over all sections)
                      ///< gets; 16..4096
  int samples = 4;    ///< MSAA samples per pixel, as in SectionPreviewOptions
  glm::dvec3 background_srgb{1, 1, 1};  ///< opaque background of each tile, sRGB 0..1
};

/// Renders every section head-on (render_section_preview(), no margin) at one common scale:
/// pixels per metre = tile_px / the largest side of any section's extent in its own (u, v)
/// frame. Each image is then centred on a square tile of tile_px x tile_px pixels filled with
/// the background, so all tiles have the same size and a section twice as wide as another
/// shows twice as wide (to within one pixel of rounding). Feed the result to compose_grid().
/// @param sections at least one, each as render_section_preview() requires
/// @returns one opaque tile_px x tile_px image per section, in order
/// @throws InternalError when sections is empty, a section is malformed or
///         tile_px is outside 16..4096
/// @throws EnvironmentError when rendering fails (see render_section_preview())
std::vector<Image> render_section_tiles(const std::vector<CrossSection>& sections,
                                        const SectionTileOptions& options = {});

/// A contact sheet of cross-sections (`cutaway variants`): render_section_tiles() of those
/// present, a tile of the background where one is missing (its reason is the caller's to
/// report), laid out by compose_grid() in `columns` columns (0: ceil(sqrt(n))), in order.
/// @pre at least one section is present
/// @throws as render_section_tiles()
Image section_sheet(std::vector<Outcome<CrossSection>> sections,
                    const SectionTileOptions& options = {}, int columns = 0);

}  // namespace cutaway
