// Skin relief maps (doc/template-format.md, Skin patterns: `relief`): the height field the
// skin's pattern layers raise or sink, baked from a skin canvas's relief channel into a
// tangent-space normal map (glTF's normalTexture; the OpenGL preview) and a height map
// (POV-Ray's bump_map). The surface keeps its shape; only its shading follows the relief.
#pragma once

#include <cstdint>
#include <vector>

#include "material/texel_bake.h"

namespace cutaway {

/// A skin's relief as textures of the skin canvas's size, row 0 at the top.
struct ReliefMaps {
  /// width * height * 3, linear: the unit normal of the relief in the texture's tangent frame,
  /// each component c stored as round(255 (c + 1) / 2). X runs across the texture (increasing
  /// u: around the section), Y up the texture (decreasing v: up the profile), Z out of the
  /// skin: glTF's normalTexture convention, which MikkTSpace and screen-derivative frames read.
  std::vector<uint8_t> normal;
  /// width * height, linear grey: the height from low_m (0) to high_m (255).
  std::vector<uint8_t> height;
  double low_m = 0, high_m = 0;  ///< the relief's lowest and highest height, metres
  double texel_m = 0;            ///< mean metres a texel spans on the surface (across and down)
};

/// Bakes the relief channel of `canvas` (rasterised, not yet dilated; TexelCanvas::relief).
/// The normal of a covered texel is normalize(-dh/dx, -dh/dy, 1) with the height's slopes
/// across and up the texture, by central differences over the covered neighbours (one-sided
/// at an island's edge, 0 with neither; columns wrap with canvas.wrap_u) divided by the metres
/// a texel spans there. Both maps are then dilated by `padding` texels and their background
/// filled (texel_bake.h), so that mip-mapping finds flat skin around the islands.
/// Deterministic.
/// @throws InternalError when the canvas has no relief channel
ReliefMaps bake_relief_maps(const TexelCanvas& canvas, int padding);

}  // namespace cutaway
