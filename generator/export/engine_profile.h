// Engine profiles: what each consumer of a glTF file needs written (vertex encoding, collision
// naming, pivots), set by one name (`--for`, a batch's `export: for`). doc/engines.md says per
// consumer what to expect, measured.
#pragma once

#include <string_view>

#include "export/gltf_export.h"

namespace cutaway {

/// The consumers a profile exists for, in the order the command line lists them.
inline constexpr std::string_view kEngineProfiles[] = {"godot", "unreal", "unity", "web",
                                                       "blender"};

/// Sets in `options` what the consumer `name` needs (the rest is left as given):
/// - godot (Godot 3, and Godot 4 before it reads KHR_mesh_quantization): float32 vertex data;
///   each piece's mesh node named "-rigid", which Godot's importer turns into a RigidBody
///   with convex shapes decomposed from the mesh (GltfCollision::GodotRigid); pivots at each
///   piece's centre of mass (a Godot body turns about its origin); no backdrop;
/// - unreal (Unreal Engine's glTF import): float32 vertex data (the importer does not promise
///   KHR_mesh_quantization); each piece's convex hulls as "UCX_<mesh>_<kk>" nodes, which the
///   import takes as the mesh's collision (GltfCollision::Unreal); pivots at each piece's centre
///   of mass; no backdrop;
/// - unity (Unity's glTFast): KHR_mesh_quantization, which glTFast reads; no collision hulls
///   (glTFast makes no colliders from names: a convex MeshCollider on the piece builds its
///   own); pivots at each piece's centre of mass; no backdrop;
/// - web (three.js and other browsers' loaders with a meshopt decoder): EXT_meshopt_compression,
///   no collision hulls among the drawn meshes, no backdrop;
/// - blender (Blender 3.4+ and the add-on): KHR_mesh_quantization, no collision hulls; the
///   backdrop kept (the add-on stages it for renders).
/// @throws InternalError for a name outside kEngineProfiles (the callers check it first)
void apply_engine_profile(std::string_view name, GltfSceneOptions& options);

}  // namespace cutaway
