// The wood of a cutting board (doc/scene-format.md, `container`; the look of issue "anatomy and
// look", item 7): the board's top seen from above as a base colour texture with the grain of
// flat-sawn wood, so that a board is not a flat brown box. The board's mesh
// (container_mesh.h) maps it onto its top, and its sides take the edge rows and columns.
#pragma once

#include <cstdint>

#include "assets/scene_assets.h"
#include "placement/container.h"

namespace cutaway {

/// Texels per millimetre of the board's texture, before the cap on its longer side.
inline constexpr double kBoardWoodTexelsPerMm = 2.0;
/// The most texels along the board texture's longer side.
inline constexpr int kBoardWoodMaxSide = 1024;

/// The board's top as an sRGB base colour texture (RGB, `name` "board_wood", row 0 at z = -depth
/// / 2, column 0 at x = -width / 2), kBoardWoodTexelsPerMm texels per millimetre, at most
/// kBoardWoodMaxSide along the longer side and at least 2 along each. The grain runs along X
/// (the board's width): growth rings cut lengthwise, as stripes about 3 mm apart (latewood
/// lines darker, 0.62 to 1.0 of `board.colour`) that Perlin noise (perlin_noise.h; Perlin 2002)
/// bends by up to about five rings over some 90 mm (the cathedral figure of flat-sawn boards),
/// with fine lengthwise streaks (the pores) and a broad tone over 100 mm. Deterministic in
/// `seed`, the board's sizes and colour.
/// @pre board.type == ContainerType::Board, width and depth positive and finite
AssetTexture board_wood_texture(const Container& board, uint64_t seed);

}  // namespace cutaway
