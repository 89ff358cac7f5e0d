// Opaque OpenGL render of a whole scene (SceneAssets): every instance of every mesh, coloured by
// its materials (vertex colours or base colour textures), seen from the scene's camera, lit by
// its lights, rendered offscreen (render/gl/gl_context.h).
#pragma once

#include "assets/scene_assets.h"
#include "npr/silhouettes.h"  // Stroke
#include "render/image/image.h"

namespace cutaway {

/// How render_scene_preview() draws. Units are in the names.
struct ScenePreviewOptions {
  int width = 0;          ///< image width, pixels; 0 = SceneAssets::width, else 1..16384
  int height = 0;         ///< image height, pixels; 0 = SceneAssets::height, else 1..16384
  int samples = 8;        ///< MSAA samples per pixel, >= 1; clamped to what GL offers
  double exposure = 1.0;  ///< scales the light of all lights and the ambient term (not the
                          ///< background), > 0 and finite
  /// Silhouette strokes (extract_strokes() for this image size) drawn over the render with
  /// draw_strokes() (render/gl/stroke_renderer.h); null or empty: none.
  const std::vector<Stroke>* strokes = nullptr;
};

/// Renders `assets` opaque from `assets.camera`: a pinhole camera at `eye` looking at `target`
/// with `up` (image x to the right of the view direction, image y toward `up`), perspective
/// with the vertical field of view `fov_y_deg`, the aspect of the image (width / height;
/// `camera.aspect` is not used), clipped to `znear`..`zfar` (metres).
///
/// Every instance places its mesh by scene point = translation + rotation * mesh point (the
/// quaternion is normalised); each mesh is uploaded once and drawn once per instance, in
/// instance order, primitive by primitive (`primitives`, their full triangles; `coarse` is not
/// used), with a depth test. Triangles are drawn from both sides (no culling) and lit
/// two-sided, so an open mesh or a flipped triangle still shades sensibly.
///
/// Shading, in linear RGB with the albedo a and the stored per-vertex `normal` (interpolated,
/// renormalised, flipped toward the eye on back faces; a zero normal falls back to the
/// triangle's own) as n, and v the unit direction to the eye:
///   base   = a * exposure * (H(n) + sum_i c_i * s_i * max(n . l_i, 0))
///            + exposure * sum_i c_i * s_i * F(v . h_i) * S_i(r)
///   colour = base * (1 - k F(n . v)) + k F(n . v) * exposure * sum_i c_i * s_i * S_i(r_k)
/// The albedo a is the primitive's material's base colour texture (sRGB, decoded to linear;
/// mipmapped, filtered trilinearly; repeating in u where `wrap_u`, else clamped, and clamped in v)
/// sampled at the mesh's interpolated `uv` (glTF convention: v = 0 at the top row) when the
/// material has one and the mesh has `uv`, else the per-vertex linear `colour`. The reflection
/// is glTF 2.0's for a dielectric (its Appendix B): F is Schlick's Fresnel from 0.04 at normal
/// incidence, S_i(r) = pi * D * V * max(n . l_i, 0) with the Trowbridge-Reitz (GGX)
/// distribution D of alpha = r^2 and Smith's height-correlated visibility V, for the light's
/// disc (angular radius angle_deg / 2; a point light has none) by Karis's representative point
/// (2013): l_i is the direction within the disc closest to v mirrored about n, and the lobe is
/// scaled by (alpha / alpha')^2 with alpha' = alpha + half the radius (radians), so that a
/// smooth face mirrors the disc at about its radiance and a rough one keeps its broad sheen.
/// r is the perceptual roughness: the material map's per texel (its G channel, as glTF viewers
/// read it: a cut face's stones, seeds and fibres duller or wetter than its flesh) where the
/// material has one (`material_texture`, RGBA) and the mesh has `uv`, else the material's
/// `pbr.roughness`. The clear layer (`pbr.clearcoat` k and `clearcoat_roughness` r_k: the wet
/// film of cut flesh, a skin's wax) is layered on top as KHR_materials_clearcoat layers it.
/// Other material channels (sheen, translucency) are not shown. Per light i, c_i is its linear
/// colour, h_i the half vector of l_i and v, and s_i = E_i / (683 pi) the
/// radiance a white Lambertian face lit head-on shows (Blender's and POV-Ray's mapping,
/// doc/lighting.md): E_i is `intensity` in lux for a directional light and `intensity` / d^2
/// (candela over squared metres to the light) for a point light. So the studio key light
/// (1639.2 lux) falling head-on shows 0.764 a plus the ambient. H(n) is a hemisphere ambient of
/// the sky's radiance S = `assets.ambient_lux` / (683 pi) from above (+Y) down to 0.4 S from the
/// ground, blended by n.y (Blender's uniform world of that radiance, with the ground's occlusion
/// that the preview does not trace), so faces turned away from every light are darker but not
/// black; without a sky (ambient_lux 0) they are black. Shadows: the shadow-casting light
/// (shadow_casting_light(), when directional) has its term c_i * s_i scaled by the fraction of
/// it that reaches the point, from a 2048 x 2048 depth map seen along it over the bounding
/// sphere of everything but the backdrop (shadow_casters_bounds(); the backdrop receives
/// shadows but casts none, and points outside the map are lit): percentage-closer soft shadows
/// (Fernando 2005), occluders searched within 12 mm, the penumbra as wide as the gap to them
/// times tan(angle_deg / 2), at least a texel, at most 12 mm, on fixed spiral taps (16 to find
/// occluders, 32 to filter: no noise). The other lights cast none. The result is written to a
/// 16-bit float framebuffer, multisampled edges are resolved in linear RGB, and each component is
/// clamped to 0..1 and encoded to sRGB8 (linear_to_srgb8). The background is `assets.background`
/// (linear RGB) everywhere nothing is drawn. The image is opaque. The result is deterministic: the
/// same assets and options give the same bytes on the same OpenGL implementation.
///
/// Creates its own offscreen OpenGL context (create_offscreen_context()) for the call.
/// @param assets  every instance's `mesh` indexes `meshes`; an instanced mesh has as many
///                normals and colours as positions (and as many finite `uv`, or none),
///                triangle indices below that count, finite positions (metres) and valid
///                primitives (check_primitives()); every texture is at least 1x1 with 3 or 4
///                channels and width * height * channels bytes of pixels; every material has
///                roughness in 0..1 and texture indices -1 or in range, its base colour
///                texture having 3 channels; rotations non-zero and finite; camera: eye, target,
///                up finite, eye != target, up not parallel to the view direction,
///                0 < fov_y_deg < 180, 0 < znear < zfar; at most 16 lights, each with finite
///                fields, intensity >= 0, a non-zero direction (directional); background
///                finite and >= 0. Meshes without instances are ignored; no instances at all
///                gives the background alone.
/// @param options see ScenePreviewOptions for ranges; the image size also comes from
///                `assets.width/height` when the options leave it 0
/// @returns an opaque image of width x height pixels, sRGB8, rows top first
/// @throws InternalError when the assets or options break the preconditions, or a
///         used texture is larger than GL_MAX_TEXTURE_SIZE
/// @throws EnvironmentError when no OpenGL context can be created or rendering fails
Image render_scene_preview(const SceneAssets& assets, const ScenePreviewOptions& options = {});

}  // namespace cutaway
