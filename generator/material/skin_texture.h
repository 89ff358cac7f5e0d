// Skin textures (paper §6, Limitations: DSs "lack information about texture details"): a swept
// skin gets texture coordinates from its sweep parameters, u = t_section (around the axis,
// repeating) and v = 1 - t_profile (top row at the top of the object), and its front colour,
// Perlin-modulated per texel in the object frame, is baked into one texture per object that
// all its pieces share (with the relief of its patterns, a normal and a height map).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "material/colour_modulation.h"
#include "material/relief_map.h"
#include "material/skin_pattern.h"
#include "model/ds_model.h"
#include "pieces/shaded_mesh.h"

namespace cutaway {

/// How skins are baked.
struct SkinTextureOptions {
  double texels_per_m = 2150;  ///< texel density on the skin (a 70 mm tomato: 476 x 236);
                               ///< a quarter of the caps': the skin's colour is smoother
  int padding = 4;             ///< rows of dilation around the baked texels
  int max_size = 2048;         ///< largest side
  bool power_of_two = false;   ///< sides powers of two (for engines that ask), not multiples of 4
};

/// The texture size of `skin` (a swept DS surface) at `options.texels_per_m`: width from its
/// longest section ring, height from its longest profile line (metres), each rounded up to a
/// multiple of 4 (GPU block compression's block; with options.power_of_two to a power of two),
/// at least 16 and at most max_size.
glm::ivec2 skin_texture_size(const DsSurface& skin, const SkinTextureOptions& options);

/// The texture coordinates of the corners of triangle `t` of `mesh` (whose `param` holds sweep
/// parameters): (t_section, 1 - t_profile), unwrapped so that a triangle across t_section = 0
/// gets u + 1 on its corners below 0.5 (the texture repeats in u), and a corner at a pole
/// (t_profile 0 or 1 with its other corners off it: one vertex for every t_section) gets the
/// mean u of the other two.
std::array<glm::dvec2, 3> skin_corner_uv(const ShadedMesh& mesh, const glm::uvec3& t);

/// Gives every vertex of `skin` (a piece's skin part, with `param`) the texture coordinates its
/// triangles ask for (skin_corner_uv), appending a copy of a vertex wherever two of its
/// triangles ask for different ones (along t_section = 0, at the poles) and re-indexing those
/// triangles. Returns the coordinates, #V of the result.
/// @throws InternalError when skin.param is not #V long
std::vector<glm::dvec2> unwrap_skin(ShadedMesh& skin);

/// A skin's baked textures, all of one size.
struct SkinTexture {
  std::vector<uint8_t> srgb;         ///< width * height * 3, sRGB: the colour
  std::optional<ReliefMaps> relief;  ///< where a pattern layer has a relief
};

/// Bakes the skins `parts` (each a piece's skin part with its unwrap_skin coordinates `uv`)
/// into one sRGB RGB texture of `size` texels repeating in u (texel_bake.h): front colours
/// interpolated, the skin's `patterns` laid over them (if not null), modulated by `modulation`
/// (if not null) with `strength`, dilated by options.padding; and where `patterns` has a
/// relief, its normal and height maps (relief_map.h). Deterministic.
SkinTexture bake_skin_texture(const std::vector<const ShadedMesh*>& parts,
                              const std::vector<const std::vector<glm::dvec2>*>& uv,
                              glm::ivec2 size, const SkinPatterns* patterns,
                              const ColourModulation* modulation, double strength,
                              const SkinTextureOptions& options);

}  // namespace cutaway
