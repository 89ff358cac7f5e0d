// glTF 2.0 export of DS models, cross-sections and whole scenes (Khronos glTF 2.0
// specification; COLOR_0 is linear RGB; lights through KHR_lights_punctual).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "assets/scene_assets.h"
#include "export/ktx2_texture.h"
#include "export/texture_image.h"
#include "model/ds_model.h"
#include "section/cross_section.h"

namespace cutaway {

/// How a DS model looks in glTF: alpha-blended surfaces so that the inner structure shows
/// (paper Fig. 9).
struct GltfModelOptions {
  double skin_alpha = 0.35;  ///< opacity of the skin, 0..1
  double inner_alpha = 0.7;  ///< opacity of every other surface, 0..1
};

/// Encodes the model as binary glTF (.glb): one mesh per DS surface with two primitives, the
/// front side (its winding, front colours) and the back side (reversed winding, back colours),
/// each single-sided, so a viewer shows each side's own colour; positions in metres (object
/// frame, +Y up), per-vertex normals, COLOR_0 linear RGB; materials alpha-blended.
/// Deterministic: the same model gives the same bytes.
std::string model_to_glb(const DsModel& model, const GltfModelOptions& options);

/// Writes model_to_glb to `path` atomically (temporary file, then rename).
/// @throws EnvironmentError when the file cannot be written
void write_model_glb(const std::filesystem::path& path, const DsModel& model,
                     const GltfModelOptions& options);

/// Encodes a cross-section as binary glTF: one mesh, one double-sided opaque primitive,
/// positions in metres (object frame), the plane normal as NORMAL, COLOR_0 linear RGB.
/// Deterministic.
std::string section_to_glb(const CrossSection& section);

/// How a scene's glTF stores its vertex data (meshoptimizer, Debian's libmeshoptimizer-dev).
enum class GltfCompression {
  /// float32 attributes: every glTF 2.0 loader reads them.
  None,
  /// KHR_mesh_quantization (listed as required): positions as normalized SHORT over each mesh's
  /// bounding cube, the cube's centre and half size folded into the nodes that use the mesh
  /// (their translation and uniform scale); normals as normalized BYTE; colours and texture
  /// coordinates in 0..1 as normalized UNSIGNED_SHORT. About 1/65535 of the largest half
  /// extent (1.5 micrometres on a 10 cm fruit), 1/127 on normals. three.js, Blender 3.4+ and
  /// the Khronos validator read it.
  Quantize,
  /// Quantize with positions on 14-bit steps (1/16383 of the largest extent: 6 micrometres on a
  /// 10 cm fruit) and normals through the octahedral filter (8-bit), each buffer view then
  /// encoded by meshoptimizer's vertex and index codecs
  /// (EXT_meshopt_compression, listed as required; the fallback buffer holds no bytes).
  /// three.js reads it with its MeshoptDecoder; Blender 3.4 does not.
  Meshopt,
};

/// How the instances' collision hulls (AssetInstance::collision) are written: as extra mesh
/// nodes under each piece's node, named as an engine's importer reads collision geometry.
enum class GltfCollision {
  None,    ///< not written
  Godot,   ///< "<piece>_collision<k>-convcolonly": Godot's convex-collision-only suffix
  Unreal,  ///< "UCX_<mesh>_<kk>": Unreal's convex collision prefix, after the render mesh
  /// No hull nodes; each piece's mesh node named "<piece>_mesh-rigid": Godot 3's importer
  /// makes it a RigidBody holding the mesh and convex shapes it decomposes from the mesh (a
  /// loose piece; its hulls under "-convcolonly" would be StaticBodies beside it).
  GodotRigid,
};

/// Whether `collision` writes hull nodes (AssetInstance::collision): every naming but None and
/// GodotRigid, whose engine makes its own shapes. Callers skip computing hulls otherwise.
inline bool writes_hull_nodes(GltfCollision collision) {
  return collision != GltfCollision::None && collision != GltfCollision::GodotRigid;
}

/// Options of the scene glTF export.
struct GltfSceneOptions {
  GltfCompression compression = GltfCompression::Quantize;
  /// Coarser levels of detail per mesh (0..4), made by meshoptimizer's simplifier: level l
  /// keeps about 2^-l of each primitive's triangles where the error stays within 2^(l-1) % of
  /// the mesh's extent, the primitives' borders (cut outlines, the seams between skin and cap)
  /// locked so that closed pieces stay closed; the same vertices, new indices. Written as
  /// glTF meshes and nodes named `<name>_LOD<l>` (the suffix Unreal and Unity take for levels)
  /// and tied to the full node by MSFT_lod, with extras.MSFT_screencoverage 0.2 * 4^-l for
  /// level l and 0 for the last (always shown); those nodes are not in the scene's node list.
  /// Viewers without MSFT_lod show the full meshes.
  int lods = 0;
  /// How base-colour textures are stored (texture_image.h); material maps are PNG, except
  /// with Ktx2, which stores every texture as KTX2 (KHR_texture_basisu, listed as required;
  /// no PNG or JPEG fallback), encoded by `basisu`.
  TextureFormat textures = TextureFormat::Jpeg;
  /// The Basis Universal encoder for Ktx2 textures (find_basisu, ktx2_texture.h).
  std::filesystem::path basisu{};
  /// Where Ktx2 encodings are kept between runs (stored_ktx2), or none: each run encodes them.
  std::optional<BlobStore> texture_store;
  /// With Ktx2: each texture also as the JPEG or PNG image the Jpeg format writes, its
  /// `source` (the KTX2 image stays its KHR_texture_basisu source, and the extension is no
  /// longer required), for readers without KTX2 (Blender's glTF importer). Both images are
  /// stored: the file grows by the JPEG and PNG bytes.
  bool texture_fallback = false;
  /// Whether the camera and the lights are written: for scenes made to be rendered, not for
  /// assets to be placed in someone else's scene (`piece` and batches leave them out unless
  /// asked).
  bool camera_and_lights = true;
  /// Collision hulls of the pieces (scenes leave them out: their pieces have settled).
  GltfCollision collision = GltfCollision::None;
  /// Whether each mesh node's origin is its mesh's centre of mass (volume_centroid; the
  /// positions stored relative to it, the node translated there), so that an engine's rigid
  /// body, which turns about its origin, turns about the piece's centre; the pieces stay
  /// assembled by the nodes' transforms. Otherwise the origin is the instance's (float
  /// positions) or the mesh's bounding-box centre (quantized).
  bool pivot_at_centre_of_mass = false;
  /// Whether the backdrop (AssetInstance::backdrop: a photographer's sweep, staging for
  /// pictures) is written, with the meshes only it uses. Engine profiles for games leave it out.
  bool backdrop = true;
  /// Members added to the scene's extras (an object; e.g. `interior_volume`, the files of the
  /// object's interior volume, volume/interior_volume.h), beside those the export writes.
  nlohmann::json scene_extras = nlohmann::json::object();
};

/// "none", "quantize" or "meshopt" as a GltfCompression.
/// @throws InternalError for any other name
GltfCompression parse_gltf_compression(std::string_view name);

/// "none", "godot", "unreal" or "godot-rigid" as a GltfCollision.
/// @throws InternalError for any other name
GltfCollision parse_gltf_collision(std::string_view name);

/// Encodes a scene as binary glTF (.glb), metres, +Y up:
/// - one mesh per AssetMesh (same order and name), one opaque single-sided primitive per
///   AssetPrimitive (one for a mesh without), all sharing the mesh's POSITION (with min/max),
///   NORMAL (renormalised), COLOR_0 (vec3, linear RGB clamped to 0..1) and TEXCOORD_0
///   accessors, stored as `options.compression` says, each with its own indices (uint16 when
///   the mesh has at most 65535 vertices, else uint32); each primitive's triangles in the
///   order meshoptimizer gives for
///   the GPU's post-transform vertex cache, the vertices in the order of their first use;
/// - the materials some primitive uses, in the order of SceneAssets::materials: vertex colour
///   times a white base colour, metallic 0, the material's roughness, and
///   KHR_materials_clearcoat (clearcoat > 0), KHR_materials_sheen (sheen not black) and
///   KHR_materials_diffuse_transmission (translucency > 0), each listed in extensionsUsed;
///   material 0 by default is "vertex colour", roughness 0.6, no extension;
/// - a root node named after the scene (SceneAssets::name), at the origin: the asset's pivot;
/// - under it, one node per AssetInstance (same order and name): rotation [x, y, z, w]
///   (normalised, w >= 0) and translation, the same whatever the compression; a piece's node
///   (PieceInfo with a template) has extras {template, seed (decimal string), cut, piece (its
///   cell), parts, volume_m3}; its one child "<name>_mesh" holds the mesh, with the mesh's
///   quantization frame (translation and uniform scale, none without compression) as its
///   transform, and with levels of detail the MSFT_lod extension; with options.collision,
///   then one node per collision hull (AssetInstance::collision), named as GltfCollision says,
///   with extras {"collision": "convex"} and a mesh of float32 POSITION (with min/max) and
///   uint32 indices, no normals, and one shared material "collision" of alpha 0, blended
///   (engines take the node as collision only and drop its mesh; viewers that do not read the
///   names show nothing; the manifest's counts leave it out);
/// with options.camera_and_lights:
/// - a node "camera" at `camera.eye` rotated so that its -Z looks at `camera.target` with +Y
///   towards `camera.up` (when `up` is parallel to the view: +Y of the scene, else -Z),
///   holding a perspective camera (yfov in radians, aspectRatio, znear, zfar);
/// - one node per AssetLight with a KHR_lights_punctual light (listed in extensionsUsed):
///   directional lights (intensity in lux) rotated so that their -Z is `direction`; point
///   lights (intensity in candela) translated to `position`, range infinite;
/// - the scene's extras: `exposure` = 1 / kLumensPerWatt (the display value per unit of the
///   lights' radiance: three.js's toneMappingExposure under LinearToneMapping, Blender's
///   exposure 0 under its Standard view) and `ambient_lux` = `assets.ambient_lux` when > 0.
/// Node order: the root, each instance's node then its mesh node and hull nodes, the camera,
/// the lights, the level nodes; the scene lists the root, the camera and the lights.
/// asset.generator is "cutaway". Deterministic: the same assets give the same bytes.
/// @throws InternalError when the assets break their documented invariants: a mesh
///   without triangles, with arrays of different lengths, an index out of range or a
///   non-finite position, primitives that do not cover its triangles in order or name a
///   material that does not exist, a material value outside 0..1; an instance whose mesh
///   index is out of range or whose rotation is
///   zero; eye == target, fov_y_deg outside (0, 180), aspect <= 0, not 0 < znear < zfar; a
///   zero light direction.
std::string scene_to_glb(const SceneAssets& assets, const GltfSceneOptions& options = {});

/// What a viewer draws of a binary glTF file: the triangles (index count / 3) and vertices
/// (POSITION count) of every primitive of the meshes of its default scene's nodes, children
/// included. The coarser MSFT_lod levels are not counted: they stand in for the full meshes.
struct GltfGeometryCounts {
  size_t triangles = 0, vertices = 0;
};

/// GltfGeometryCounts of `glb` (the bytes of a .glb file, such as scene_to_glb's), read from
/// its JSON chunk.
/// @throws EnvironmentError "not a binary glTF file: REASON" when the bytes are not one
///         with indexed triangle primitives
GltfGeometryCounts count_glb_geometry(std::string_view glb);

/// Writes the scene as glTF, the format chosen by the extension of `path` (case-insensitive):
/// ".glb": binary glTF, one file (the bytes of scene_to_glb);
/// ".gltf": JSON, 2-space indented, with its binary buffer in a file beside it with the same
///   stem and extension ".bin" (referenced by a relative, percent-encoded URI); otherwise the
///   same content as the .glb.
/// Files are written to temporaries in the target directory and renamed into place (the .bin
/// first); a failure leaves neither file (should the last rename fail, the new .bin, which
/// may have replaced an older one, is removed). The directory must exist (it is not created).
/// @throws InternalError for any other extension and for invalid assets (see
///   scene_to_glb); EnvironmentError when the directory is missing or a file cannot be
///   written.
void write_scene_gltf(const std::filesystem::path& path, const SceneAssets& assets,
                      const GltfSceneOptions& options = {});

}  // namespace cutaway
