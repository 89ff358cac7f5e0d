// Baking surface attributes into texels (the cap atlas and the skin texture): triangles mapped
// to texel space are rasterised at texel centres with their vertex colours and material
// channels interpolated barycentrically and the Perlin colour modulation evaluated per texel in
// the object frame; islands are then dilated and the background filled by pull-push so that
// mip-mapping and JPEG do not bleed a black background into their edges.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/huge_page_buffer.h"
#include "material/colour_modulation.h"
#include "material/skin_pattern.h"
#include "pieces/shaded_mesh.h"

namespace cutaway {

/// A texture being baked: linear values per texel, row 0 at the top.
struct TexelCanvas {
  int width = 0, height = 0;
  /// With `wrap_u`, texel columns repeat (x modulo width): a texture addressed with u beyond
  /// 0..1 under glTF's default REPEAT wrapping (the skin's section parameter runs around).
  bool wrap_u = false;
  HugePageVector<glm::dvec3> colour;    ///< width * height, linear RGB
  HugePageVector<glm::dvec2> material;  ///< width * height, (roughness, translucency)
  HugePageVector<uint8_t> covered;      ///< width * height, 1 where baked or dilated
  /// Empty, or width * height (set by the caller before rasterise to bake the skin's relief):
  /// per texel the skin's relief height (SkinPatterns::height, metres) and the metres one texel
  /// spans across (x) and down (y) on the surface there. Not dilated or filled.
  HugePageVector<glm::dvec3> relief;

  /// An empty (black, uncovered) canvas of w x h texels.
  TexelCanvas(int w, int h, bool wrap);
};

/// Rasterises every triangle of `mesh` at `texel` (#V positions in texel units: x right, y down;
/// texel (i, j) has its centre at (i + 0.5, j + 0.5)) into `canvas`: each texel whose centre
/// lies in a triangle gets the barycentric interpolation of its vertices' colour and material
/// channels; the colour then gets the skin's `patterns` (if not null; the canvas is a skin
/// texture, so texel (i, j) lies at t_section (i + 0.5) / width and t_profile 1 - (j + 0.5) /
/// height) and is modulated by `modulation` (if not null), both at the interpolated position
/// (metres, object frame), the modulation with `strength`; the modulation's cells with a
/// roughness of their own move the material channels too. Where the canvas has a `relief`
/// channel and `patterns` is not null, the texel also gets its relief. Later triangles overwrite
/// earlier ones. Bands of rows are baked on all cores; the canvas does not depend on them.
void rasterise(const ShadedMesh& mesh, std::span<const glm::dvec2> texel,
               const SkinPatterns* patterns, const ColourModulation* modulation, double strength,
               TexelCanvas& canvas);

/// `rings` rings of dilation: each uncovered texel with covered 8-neighbours takes their mean.
void dilate(TexelCanvas& canvas, int rings);

/// Fills every texel still uncovered (after rasterise and dilate) by pull-push (Gortler et al.
/// 1996, "The Lumigraph" §3.4; the hole filling of texture atlases): the covered texels are
/// averaged into a pyramid of half-size levels, each level's empty texels taken from the
/// bilinear upsampling of the next coarser one, so the background becomes a smooth extension
/// of the islands. Covered texels keep their values. Mip-mapping then blends the islands with
/// their own colours at every level, not with black, and JPEG spends no bits on edges between
/// islands and background. A canvas without a covered texel stays as it is. Deterministic.
void fill_background(TexelCanvas& canvas);

/// The canvas at half its width and height (each rounded up): every texel the mean of the 2 x 2
/// texels it covers (fewer at an odd edge), covered where any of them is. Texture coordinates
/// address both alike where width and height are even.
TexelCanvas half_size(const TexelCanvas& canvas);

/// The colours as 8-bit sRGB RGB (width * height * 3).
std::vector<uint8_t> srgb_pixels(const TexelCanvas& canvas);

/// The material channels as an 8-bit linear RGBA material map (width * height * 4): R 255
/// (no occlusion), G roughness, B 0 (not metallic), A translucency; the channels glTF's
/// metallicRoughnessTexture and KHR_materials_diffuse_transmission's texture read.
std::vector<uint8_t> material_pixels(const TexelCanvas& canvas);

/// Mean and spread (max - min) of the material channels over the covered texels.
struct MaterialStats {
  glm::dvec2 mean{0.0}, spread{0.0};
};
MaterialStats material_stats(const TexelCanvas& canvas);

}  // namespace cutaway
