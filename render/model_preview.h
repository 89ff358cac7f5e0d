// Preview image of a DS model: every surface see-through, so the inner structure shows (paper
// Fig. 9), rendered offscreen with OpenGL (render/gl/gl_context.h) and written as PNG.
#pragma once

#include <glm/vec3.hpp>

#include "model/ds_model.h"
#include "render/image/image.h"

namespace cutaway {

/// How render_model_preview() draws. Units are in the names; colours say sRGB or linear.
struct PreviewOptions {
  int width = 800, height = 800;        ///< image size, pixels; 1..16384 (and what GL allows)
  int samples = 4;                      ///< MSAA samples per pixel, >= 1; clamped to what GL offers
  double azimuth_deg = 35;              ///< camera orbit about +Y; 0 looks from +Z toward -Z
  double elevation_deg = 25;            ///< camera height above the XZ plane; -89..89
  double fov_deg = 30;                  ///< full field of view of the image's shorter side; 1..170
  double skin_alpha = 0.35;             ///< opacity of the skin (surfaces[0]), 0..1
  double inner_alpha = 0.7;             ///< opacity of every other surface, 0..1
  glm::dvec3 background_srgb{1, 1, 1};  ///< opaque background, sRGB 0..1
};

/// Renders `model` with every surface see-through, after the paper's Fig. 9 (Takayama et al.
/// 2010, "Volumetric modeling with diffusion surfaces").
///
/// Each surface shows its per-vertex `front` colour (linear RGB) where it is seen from the side
/// its normal points to (CCW winding = front) and its `back` colour where seen from behind; a
/// side marked hollow (`visible_front`/`visible_back` false) shows the other side's colour.
/// Lighting is in linear RGB: ambient + Lambert from a key light near the eye, two-sided, plus a
/// rim term; smooth normals come from the mesh (area-weighted face normals), not from stored
/// normals. All triangles of all surfaces are sorted back to front by view-space centroid depth
/// (ties by index) and alpha-blended without a depth test, into a multisampled framebuffer.
/// The camera orbits the centre of `model.bbox_min/max` (metres, +Y up) at the distance where the
/// sphere about that centre through the farthest vertex fills the field of view with a small
/// margin; the background is opaque. The result is deterministic:
/// the same model and options give the same bytes on the same OpenGL implementation.
///
/// Creates its own offscreen OpenGL context (create_offscreen_context()) for the call.
/// @param model   at least one triangle; bbox_min/max as set by update_bounds(), with a
///                positive, finite diagonal
/// @param options see PreviewOptions for ranges
/// @returns an opaque image of options.width x options.height pixels
/// @throws InternalError when the model or options break the preconditions
/// @throws EnvironmentError when no OpenGL context can be created or rendering fails
Image render_model_preview(const DsModel& model, const PreviewOptions& options);

}  // namespace cutaway
