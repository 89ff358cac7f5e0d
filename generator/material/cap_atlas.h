// Baked cap textures (paper §6, Limitations: DSs "lack information about texture details"):
// the cut faces of one object's pieces get UVs from their plane frames, packed into
// one texture atlas, and their colours (PMVC-diffused at the cap's vertices, Perlin-modulated
// per texel in the object frame) baked at texel resolution, so detail finer than the cap mesh
// survives and the geometry no longer has to carry the colour.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "material/colour_modulation.h"
#include "pieces/pieces.h"

namespace cutaway {

/// How caps are baked.
struct CapAtlasOptions {
  double texels_per_m = 8600;  ///< texel density on the cut plane (a 60 mm cap: 516 texels)
  int padding = 4;             ///< texels around each island, filled by dilation so that
                               ///< mip-mapping does not bleed the background into its edges
  int max_size = 4096;         ///< largest atlas side, a multiple of kAtlasStep; denser
                               ///< islands are scaled down to fit
  bool power_of_two = false;   ///< sides powers of two (for engines that ask for them), not
                               ///< multiples of kAtlasStep; max_size must be one too
};

/// Sides of cap atlases are multiples of this: their half-size material maps' are then
/// multiples of 4, the block size of GPU texture compression (BCn, ETC, ASTC 4x4).
inline constexpr int kAtlasStep = 8;

/// Material channels varying less than this over an object's caps (half an 8-bit step) make no
/// material map: the cut material's factors carry their mean.
inline constexpr double kMaterialMapSpread = 0.5 / 255;

/// One object's cap atlas.
struct CapAtlas {
  int width = 0, height = 0;  ///< texels (0 x 0: no caps); both multiples of kAtlasStep
  std::vector<uint8_t> srgb;  ///< width * height * 3, row 0 at the top (v = 0), sRGB 8-bit
  /// width * height: 1 on the islands and their padding, 0 on the background (which holds a
  /// smooth extension of the islands, fill_background).
  std::vector<uint8_t> covered;
  /// material_width * material_height * 4: the material map (texel_bake.h, material_pixels) at
  /// half the colour's resolution over the same layout (the same texture coordinates address
  /// it), or empty where the material channels do not vary over the caps (spread below
  /// kMaterialMapSpread). Half: roughness and translucency change more slowly than colour
  /// within the flesh, and the eye resolves them less; it is a quarter of the texels.
  std::vector<uint8_t> material;
  int material_width = 0, material_height = 0;  ///< texels of the material map
  glm::dvec2 material_mean{0.0};  ///< mean (roughness, translucency) over the caps' texels,
                                  ///< to 1e-6 (the diffusion's single precision)
  double texels_per_m = 0;        ///< the density used (options.texels_per_m, or less to fit)
  /// Per piece of the input, per vertex of merge_parts(piece): texture coordinates in 0..1
  /// (glTF convention: u to the right, v down from the top row); (0, 0) on the skin and walls.
  std::vector<std::vector<glm::dvec2>> uv;
};

/// Bakes the caps of `pieces` (all cut from one object by one cut_pieces call whose sections
/// are `sections`) into one atlas. Cap triangles are mapped by the plane frame of their section
/// (u_axis, v_axis) at texels_per_m. Caps of one plane whose bounding rectangles overlap share
/// one island: the two caps of a cut cover the same region and carry the same field there, so
/// they address the same texels and the plane is baked once, not once per side. Islands are
/// packed with stb_rect_pack in the order of their first cap (piece and part order), into the
/// atlas of fewest texels among widths from the square root of their area to twice that (sides
/// multiples of kAtlasStep, not powers of two: the salad's caps take 5.6 M texels, not 7.1 M).
/// Every texel whose centre lies in a cap triangle gets the barycentric interpolation of the
/// triangle's vertex colours (linear RGB) and material channels, the colour modulated by
/// `modulation` at the texel's point in the object frame with `strength` (none when modulation
/// is null), then encoded as sRGB (texel_bake.h); the islands are dilated by `padding` texels
/// and the background filled by pull-push (fill_background). Deterministic.
/// With options.power_of_two the sides are powers of two, the widths tried doubling.
/// @throws InternalError when texels_per_m <= 0, padding < 0, max_size < 16 or max_size is no
///         multiple of kAtlasStep (with power_of_two: no power of two)
CapAtlas bake_cap_atlas(const std::vector<const Piece*>& pieces,
                        const std::vector<CrossSection>& sections,
                        const ColourModulation* modulation, double strength,
                        const CapAtlasOptions& options);

}  // namespace cutaway
