// Preview image of a cross-section: the coloured cut face seen head-on (paper §3.2, Fig. 3),
// rendered offscreen with OpenGL (render/gl/gl_context.h).
#pragma once

#include <glm/vec3.hpp>

#include "render/image/image.h"
#include "section/cross_section.h"

namespace cutaway {

/// How render_section_preview() draws. Units are in the names; colours say sRGB or linear.
struct SectionPreviewOptions {
  int width = 800;       ///< image width, pixels; 1..16384 (and what GL allows)
  int height = 0;        ///< image height, pixels; 0 = from the aspect of the section's extent
                         ///< (with margins), else 1..16384
  int samples = 4;       ///< MSAA samples per pixel, >= 1; clamped to what GL offers
  double margin = 0.04;  ///< empty border on each side, as a fraction of the longer side of
                         ///< the section's extent; 0..1
  glm::dvec3 background_srgb{1, 1, 1};  ///< opaque background, sRGB 0..1
};

/// Renders the cut face of `section` as seen head-on from the side its plane normal points to
/// (the view of the paper's Fig. 3, §3.2; Takayama et al. 2010, "Volumetric modeling with
/// diffusion surfaces"): orthographic, image x along `section.u_axis` (left to right), image y
/// along `section.v_axis` (bottom to top), so a counter-clockwise triangle stays
/// counter-clockwise on screen. The extent of all vertices in that frame, grown by
/// `options.margin`, is fitted into the image at one scale for both axes (square pixels) and
/// centred; when `options.height` is 0 the height follows the extent's aspect.
///
/// Colour is the per-vertex linear RGB `section.colour`, interpolated linearly across each
/// triangle (Gouraud) in linear RGB, unlit; 32-bit float framebuffer, multisampled edges
/// resolved in linear RGB, then encoded to sRGB8 on the CPU (a vertex colour c shows as
/// linear_to_srgb8(c) per component; values outside 0..1 are clamped). The image is opaque.
/// The result is deterministic: the same section and options give the same bytes on the same
/// OpenGL implementation.
///
/// Creates its own offscreen OpenGL context (create_offscreen_context()) for the call.
/// @param section at least one triangle; colour.size() == position.size(); triangle indices
///                < position.size(); positions finite, metres; u_axis, v_axis unit and
///                orthogonal (as make_cross_section() returns them); an extent of positive
///                width and height in the (u, v) frame
/// @param options see SectionPreviewOptions for ranges
/// @returns an opaque image of options.width x (options.height, or the fitted height) pixels,
///          sRGB8, rows top first
/// @throws InternalError when the section is empty or malformed, or the options are
///         out of range
/// @throws EnvironmentError when no OpenGL context can be created or rendering fails
Image render_section_preview(const CrossSection& section, const SectionPreviewOptions& options);

}  // namespace cutaway
