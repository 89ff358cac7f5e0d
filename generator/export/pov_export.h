// POV-Ray 3.7 export of a whole scene (doc/architecture.md, Data flow: SceneAssets -> export;
// doc/algorithms.md §7: `assumed_gamma 1.0` with linear colours; POV-Ray 3.7 documentation,
// "mesh2", "camera", "light_source").
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "assets/scene_assets.h"
#include "export/texture_image.h"
#include "npr/silhouettes.h"  // Stroke

namespace cutaway {

/// Encodes `assets` as a self-contained POV-Ray 3.7 scene file (no #include).
///
/// What the text holds, in this order:
/// - a comment header (generator, scene name, units: metres, colours: linear RGB);
/// - `#version 3.7;` and `global_settings { assumed_gamma 1.0 }`: every colour is written as
///   the linear RGB of the assets, and POV-Ray encodes the output image (sRGB PNG);
/// - `background` (linear RGB);
/// - the camera, written with explicit `location`, `direction`, `right` and `up` vectors in scene
///   coordinates and no `look_at`: forward = normalize(target - eye), right = normalize(forward x
///   up), true up = right x forward, direction = forward / (2 tan(fov_y / 2)), `right` = right *
///   aspect, `up` = true up. POV-Ray sends the ray of image point (u, v) in [-1/2, 1/2]^2 (u to
///   the right, v up) along direction + u right + v up, which is plain linear algebra, so its
///   left-handed convention never enters and the image matches the OpenGL/glTF view of the same
///   camera (not mirrored). The image is stretched when the render's width/height differs
///   from `camera.aspect`; znear/zfar are not used.
/// - one `light_source` per light, with this brightness mapping (a white surface with diffuse 1,
///   lit head-on by E lux, shows E / 683 / pi, the Lambertian radiance in W/m^2/sr under
///   exposure 1 / kLumensPerWatt; this is what Blender's Standard view and three.js with
///   toneMappingExposure 1 / 683 show):
///   - directional: a `parallel` light at scene centre - direction * (10 r + 10 m), where r is
///     the radius of the instances' bounding sphere, pointing at the centre, with colour
///     `colour * intensity / 683 / pi`;
///   - point: at `position`, with `fade_distance 0.01 fade_power 2` and colour
///     `colour * intensity / 683 / (2 pi 0.01^2)`, so that at a distance d >> 1 cm the
///     brightness is colour * intensity / 683 / (pi d^2), the inverse-square law of `intensity`
///     candela (POV-Ray's
///     attenuation is 2 / (1 + (d / fade_distance)^fade_power); it stays finite within 1 cm);
///   only the brightest light casts shadows (the others are `shadowless`, so shadows are
///   filled in rather than black);
/// - `global_settings { assumed_gamma 1.0 ambient_light rgb S }`, S = ambient_lux / (683 pi) the
///   sky's radiance (0 without a sky), so that with the lights above a white face shows what it
///   shows in Blender under the Standard view (doc/lighting.md);
/// - `#declare Cutaway_Finish`: ambient 1, diffuse 1, specular 0.25, roughness 0.02 (a
///   small, sharp highlight as on moist fruit), the finish of material 0; then
///   `#declare Cutaway_Finish_<k>` for every other material k: ambient 1, diffuse 1 (with
///   backside illumination `translucency` when translucent), specular 0.625 (1 - roughness),
///   roughness 0.0005 + 0.05 roughness^2, and for a clear coat phong 0.6 clearcoat min(1,
///   (0.15 / (clearcoat_roughness + 0.05))^1.5) (a rough film's highlight as dim as glTF's
///   spread lobe) and phong_size round(4 / (clearcoat_roughness + 0.05)); sheen is not shown;
/// - each mesh with at least one triangle declared ONCE as `#declare Mesh_<k>_<name> = mesh2`:
///   vertex_vectors (metres), normal_vectors (omitted when the mesh has no normals; a zero or
///   non-finite normal is replaced by the area-weighted normal of its triangles), texture_list
///   with one texture per distinct pair of vertex colour and the finish of the material of a
///   face using it (deduplicated by their written text, in order of first use), face_indices
///   with three texture indices per face (POV-Ray interpolates the vertex colours across each
///   triangle). The lists hold one item per line, without spaces or indentation: positions
///   with 6 significant digits, normals with 4, uv with 5. Meshes without triangles are left
///   out, with their instances.
/// - one `object { Mesh_<k>_<name> matrix <...> }` per instance: the 3x3 rotation of the
///   (normalised) quaternion and the translation in POV-Ray's row-vector `matrix` form.
///
/// Identifiers are `Mesh_<k>_` + the mesh name with every character outside [A-Za-z0-9_]
/// replaced by '_', cut to 40 characters (POV-Ray's limit); names in comments are sanitised the
/// same way. Numbers are written with std::to_chars (shortest of %g with 6 significant digits
/// unless said otherwise,
/// independent of the C locale, -0 written as 0), so the same assets give byte-identical text.
///
/// @param assets meshes with normal.size() == position.size() or 0, colour.size() ==
///               position.size(), triangle indices < position.size(); instances with mesh
///               indices into `meshes`; all numbers finite; camera eye != target, up not
///               parallel to the view direction, 0 < fov_y_deg < 180, aspect > 0; lights with a
///               non-zero direction (directional) and intensity >= 0
/// - with `strokes` (extract_strokes() for an image assets.width x assets.height), after the
///   instances: `#declare Cutaway_Stroke_Finish` (emission 1, no diffuse or specular) and one
///   `union { sphere {...} cone {...} sphere {...} ... }` per stroke: a sphere at every point
///   and a cone between neighbours (the tube of a linear sphere_sweep; POV-Ray's own
///   sphere_sweep shows spikes on strokes this thin), with its colour and `no_shadow`. A point
///   at depth d along the view direction with width w pixels gets the radius
///   r = w / 2 * d * 2 tan(fov_y / 2) / assets.height (so it covers w pixels in a render of that
///   height) and moves toward the eye by r; a closed stroke repeats its first point; points
///   behind the eye or within 0.1 micrometre of the previous one are left out, and strokes left
///   with fewer than 2 points are skipped.
///
/// @throws InternalError naming the mesh, instance or light that breaks a precondition
/// - with `texture_files` (texture_file_names()): faces whose material has a base colour texture
///   (and whose mesh has uv) get one texture each, `uv_mapping` with `image_map { png NAME
///   interpolate 2 }` (`jpeg` for a NAME ending in .jpg) and the material's finish; such meshes add
///   uv_vectors (v flipped: POV-Ray counts from the bottom row) and no uv_indices (POV-Ray then
///   uses the face indices). Without, those faces keep their vertex colours.
std::string scene_to_pov(const SceneAssets& assets, const std::vector<Stroke>* strokes = nullptr,
                         const std::vector<std::string>& texture_files = {});

/// Writes scene_to_pov(assets) to `path` atomically (write_file_atomically(): a temporary file,
/// then rename; a failed run leaves no partial file).
/// @throws InternalError as scene_to_pov
/// @throws EnvironmentError when the file cannot be written
/// With `textures`, the textures are written first, as image files of that format beside it
/// (texture_file_names(), each atomically; Ktx2 as Jpeg: image_file_format), and the scene
/// uses them.
void write_scene_pov(const std::filesystem::path& path, const SceneAssets& assets,
                     const std::vector<Stroke>* strokes = nullptr,
                     std::optional<TextureFormat> textures = std::nullopt);

}  // namespace cutaway
