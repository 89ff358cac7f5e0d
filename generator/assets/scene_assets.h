// What a scene becomes before export (doc/architecture.md, Key types): triangle meshes with
// per-vertex colours, instances of them with transforms, a camera and lights. glTF, POV-Ray and
// the OpenGL preview all read this; none of them knows about templates or cuts.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/ext/vector_uint3.hpp>

#include "base/coloured_mesh.h"
#include "base/outcome.h"
#include "model/pbr_material.h"

namespace cutaway {

/// `name` with every byte outside [A-Za-z0-9] replaced by '_': a name every exporter accepts
/// (glTF, POV-Ray identifiers). Locale-independent.
inline std::string asset_name(std::string_view name) {
  std::string s(name);
  for (char& c : s) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    if (!ok) c = '_';
  }
  return s;
}

/// An image for texturing, 8 bits per channel, row 0 at the top: a base colour (RGB, sRGB), a
/// material map (RGBA, linear: G roughness, B metallic, A translucency; the channels glTF's
/// metallicRoughnessTexture and KHR_materials_diffuse_transmission's texture read), a normal
/// map (RGB, linear: relief_map.h) or a height map (grey, linear).
struct AssetTexture {
  std::string name;
  int width = 0, height = 0;
  int channels = 3;             ///< 1 (grey), 3 (RGB) or 4 (RGBA)
  std::vector<uint8_t> pixels;  ///< width * height * channels, row by row
  bool wrap_u = false;          ///< repeats in u (addressed beyond 0..1), clamped in v
  /// Holds data, not colour (material, normal and height maps): stored losslessly (PNG) and
  /// read without sRGB decoding. Base colours are sRGB (false).
  bool linear = false;
};

/// A named material. Its base colour is the vertex colours, or its texture when it has one
/// (then the mesh's uv addresses it and the vertex colours are only a fallback for exporters
/// without textures).
struct AssetMaterial {
  std::string name;  ///< unique in the scene
  PbrMaterial pbr;
  int base_colour_texture = -1;  ///< index into SceneAssets::textures, or -1
  /// Index into SceneAssets::textures of an RGBA material map (roughness, translucency), or -1.
  /// With one, pbr.roughness and pbr.translucency are the map's means (for renderers that
  /// cannot read it), and the map holds the values themselves (glTF factors 1).
  int material_texture = -1;
  /// Index of a tangent-space normal map (RGB, linear; glTF normalTexture's convention:
  /// relief_map.h) shading the skin's relief, or -1. Its mesh needs uv.
  int normal_texture = -1;
  /// Index of the same relief as a height map (grey, linear, 0 lowest) for renderers that bump
  /// by height (POV-Ray's bump_map), or -1; with one, the relief's slope that one full step of
  /// the map (0 to 1) between neighbouring texels stands for: height range / metres per texel.
  int height_texture = -1;
  double height_bump = 0;
};

/// Triangles [first, first + count) of a mesh, drawn with one material.
struct AssetPrimitive {
  size_t first = 0, count = 0;
  int material = 0;  ///< index into SceneAssets::materials
  /// Empty, or the same surface in fewer triangles (over the mesh's vertices) for exporters
  /// that take its colour from the material's texture: a cut face's outline triangulated
  /// (coarse_cap_triangles), whose inner vertices only carried colour.
  std::vector<glm::uvec3> coarse;
};

/// One triangle mesh in its own frame (ColouredMesh: metres, linear colours, triangles
/// counter-clockwise seen from outside), named, with texture coordinates and materials.
struct AssetMesh : ColouredMesh {
  std::string name;            ///< unique in the scene, [A-Za-z0-9_]+
  std::vector<glm::dvec2> uv;  ///< #V texture coordinates 0..1 (glTF: v down from the
                               ///< top row), or empty: no textured material
  /// The triangles by material, in order, covering all of them without gaps (a piece: skin
  /// and walls, then caps). Empty: one primitive of material 0.
  std::vector<AssetPrimitive> primitives;
};

/// The triangles an exporter writes for primitive `p` of `mesh`: its coarse ones when its
/// colour comes from a texture (`textured`) and it has them, else its own range of
/// mesh.triangle.
std::span<const glm::uvec3> primitive_triangles(const AssetMesh& mesh, const AssetPrimitive& p,
                                                bool textured);

/// The centre of the volume `mesh` encloses (uniform density; its triangles taken as a closed
/// surface, tetrahedra from the origin summed with their signed volumes), metres, in the mesh's
/// frame; the centre of its bounding box when it encloses no volume (an open sheet, a point).
/// Where a rigid body made of it turns (an engine profile's pivot, gltf_export.h).
glm::dvec3 volume_centroid(const ColouredMesh& mesh);

/// Whether the primitives of `mesh` suit a scene of `materials` materials (else what is wrong,
/// in words): they must cover its triangles in order, none empty, each naming an existing
/// material (no primitives: one of material 0, which must exist).
Check check_primitives(const AssetMesh& mesh, size_t materials);

/// What a placed piece is, for the people who use the asset (glTF node extras).
struct PieceInfo {
  std::string template_name;       ///< empty: not a piece (a container)
  uint64_t seed = 0;               ///< the variant's seed
  std::string cut;                 ///< cut_label() of its cut
  int cell = -1;                   ///< its cell of the cut (the piece index)
  std::vector<std::string> parts;  ///< the kinds of its parts: "skin", "wall", "stone", "cap"
  double volume_m3 = 0;            ///< enclosed volume, cubic metres
};

/// A convex collision part of an instance: a closed convex triangle mesh in the instance's
/// frame (metres), triangles counter-clockwise seen from outside.
struct AssetHull {
  std::vector<glm::dvec3> position;  ///< #corners >= 4
  std::vector<glm::uvec3> triangle;  ///< indices below #corners
};

/// One placed copy of a mesh: scene point = translation + rotation * (mesh point).
struct AssetInstance {
  std::string name;                 ///< unique in the scene
  int mesh = -1;                    ///< index into SceneAssets::meshes
  glm::dquat rotation{1, 0, 0, 0};  ///< unit quaternion (w, x, y, z)
  glm::dvec3 translation{0.0};      ///< metres
  PieceInfo piece;                  ///< for pieces
  /// The convex parts a physics engine collides it as (empty: none written).
  std::vector<AssetHull> collision{};
  /// Staging that only receives shadows and light (the backdrop, assets/backdrop.h): it casts
  /// no shadow and does not count in shadow_casters_bounds.
  bool backdrop = false;
};

/// A pinhole camera in the scene frame (+Y up, metres).
struct AssetCamera {
  glm::dvec3 eye{0, 0.3, 0.3}, target{0.0}, up{0, 1, 0};
  double fov_y_deg = 40;           ///< vertical field of view, degrees
  double aspect = 4.0 / 3;         ///< width / height
  double znear = 0.01, zfar = 10;  ///< metres
};

/// Whether `camera` is sound (else what is wrong, in words): the one camera rule every exporter
/// and renderer applies. Eye, target and up finite; eye != target; fov_y_deg in (0, 180);
/// aspect positive and finite; 0 < znear < zfar, zfar finite; and, with `needs_up` (POV-Ray
/// and OpenGL build their frame from it; glTF's look rotation does not), up not zero and not
/// parallel to the view direction: |normalize(target - eye) x up| > 1e-9 |up|.
Check check_camera(const AssetCamera& camera, bool needs_up = true);

/// An up vector for a camera looking along `forward` (non-zero) that is never parallel to it:
/// +Y of the scene, or -Z of the scene when `forward` is within 0.5 degrees of straight up or
/// down (a top-down picture then has -Z, away from the default camera side, at its top).
glm::dvec3 stable_camera_up(const glm::dvec3& forward);

/// The camera's orthonormal frame, as glm::lookAt builds it: forward = normalize(target - eye),
/// right = normalize(forward x up), up = right x forward (unit vectors, scene frame).
/// @pre eye != target and `up` not parallel to the view direction
struct CameraFrame {
  glm::dvec3 forward, right, up;
};
CameraFrame camera_frame(const AssetCamera& camera);

/// Scene (metres) -> view transform: the camera at the origin looking down -z with y up
/// (glm::lookAt(eye, target, up); its rows are camera_frame's right, up and -forward).
/// @pre as camera_frame
glm::dmat4 view_from_scene(const AssetCamera& camera);

/// The focal length in pixels of an image `height_px` pixels tall, with square pixels:
/// height_px / (2 tan(fov_y / 2)).
double focal_length_px(const AssetCamera& camera, int height_px);

enum class LightType { Directional, Point };

/// Lumens per watt of light at 555 nm, the factor between photometric and radiometric units:
/// glTF importers such as Blender's turn a directional light's lux into W/m^2 (a sun's
/// strength) by dividing by it, and our renderers (the OpenGL preview, POV-Ray) show a
/// Lambertian surface lit head-on by E lux at the radiance E / kLumensPerWatt / pi times its
/// albedo, as Blender's Standard view does.
constexpr double kLumensPerWatt = 683.0;

/// A light (the glTF KHR_lights_punctual model): directional lights shine along `direction`
/// with `intensity` in lux; point lights sit at `position` with `intensity` in candela.
struct AssetLight {
  std::string name;
  LightType type = LightType::Directional;
  glm::dvec3 position{0.0};               ///< point: metres
  glm::dvec3 direction{0, -1, 0};         ///< directional: unit, the way the light travels
  glm::dvec3 colour{1, 1, 1};             ///< linear RGB
  double intensity = 3 * kLumensPerWatt;  ///< lux (directional) or candela (point)
  /// Directional: the apparent diameter of its source, degrees (Blender's sun angle), 0 to
  /// 180: the softness of its shadows; 0 a point-like sun with sharp shadows.
  double angle_deg = 0;
};

/// A whole scene ready for export: meshes (pieces, container), their instances, camera, lights.
struct SceneAssets {
  std::string name;
  /// Material 0 is the plain default every mesh without primitives uses.
  std::vector<AssetMaterial> materials{AssetMaterial{"vertex colour", PbrMaterial{}, -1}};
  std::vector<AssetTexture> textures;
  std::vector<AssetMesh> meshes;
  std::vector<AssetInstance> instances;
  AssetCamera camera;
  std::vector<AssetLight> lights;
  /// Illuminance (lux) of the uniform sky the lights were chosen with: what a renderer adds
  /// as a world or ambient light (Blender: world strength ambient_lux / (683 pi)); 0: none.
  double ambient_lux = 0;
  glm::dvec3 background{1, 1, 1};  ///< linear RGB
  int width = 1280, height = 960;  ///< pixels of renders
};

/// The triangles a file of `assets` draws: over every instance, each primitive of its mesh as
/// an exporter with textures writes it (primitive_triangles, textured where the primitive's
/// material has a base colour texture and the mesh uv): coarse cut faces where their colour is
/// a texture, the full triangles elsewhere. Levels of detail and collision hulls are not
/// counted (alternatives, not drawn). @pre check_assets(assets) holds
size_t drawn_triangles(const SceneAssets& assets);

/// A sphere about the placed vertices of some instances (scene frame, metres).
struct BoundingSphere {
  glm::dvec3 centre{0.0};
  double radius = 0;
};

/// The bounding sphere of what casts shadows in `assets`: centred on the box of the placed
/// vertices of every instance but the backdrop (AssetInstance::backdrop), out to the farthest of
/// them. No such vertex: centre 0, radius 0. @pre rotations non-zero
BoundingSphere shadow_casters_bounds(const SceneAssets& assets);

/// The index of the light that casts shadows in every renderer (the others fill them in, as
/// the sky does): the brightest by `intensity`, the first of equals; -1 without lights.
int shadow_casting_light(const SceneAssets& assets);

/// What an exporter or renderer tolerates beyond the rules every one of them applies.
struct AssetRules {
  bool camera_needs_up = true;  ///< check_camera's needs_up (glTF: false)
  /// Zero or non-finite shading normals are accepted: the consumer replaces them (glTF,
  /// POV-Ray). Otherwise every normal must be finite.
  bool normals_repaired = false;
  bool meshes_need_triangles = false;  ///< every mesh has a vertex and a triangle (glTF)
  /// Every primitive of a textured material has uv (glTF). Otherwise a mesh without uv
  /// shows its vertex colours whatever its material (the previews).
  bool textures_need_uv = false;
};

/// Whether `assets` are sound (else what is wrong, in words naming the element): the one
/// validation of SceneAssets every exporter and renderer applies, with `rules` for what each
/// tolerates. At least one material (material 0). Textures: at least 1 x 1, 3 or 4 channels, width
/// * height * channels bytes. Materials: PbrMaterial fields in range, texture indices -1 or valid,
/// base colour textures RGB. Meshes (all, instanced or not): #V normals and colours, positions and
/// colours finite, uv #V or empty and finite, triangle and coarse indices below #V,
/// check_primitives. Instances: an existing mesh, a finite non-zero rotation, a finite translation,
/// collision hulls with >= 4 finite corners, >= 4 triangles and indices in range. The camera
/// (check_camera). Lights: finite, intensity and colour >= 0, directional ones with a non-zero
/// direction, angle_deg in 0..180. The background finite and >= 0.
Check check_assets(const SceneAssets& assets, const AssetRules& rules = {});

/// Throws InternalError("WHO: reason") when check_assets(assets, rules) fails: the
/// precondition check at the top of every exporter and renderer.
void require_valid_assets(const SceneAssets& assets, const AssetRules& rules,
                          const std::string& who);

}  // namespace cutaway
