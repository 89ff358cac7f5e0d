// glTF meshes: one scene mesh (AssetMesh) written as glTF meshes over shared vertex
// accessors: its vertices welded where they write alike and ordered for the GPU's vertex cache,
// one primitive per material range, and coarser levels of detail by meshoptimizer's
// simplifier. A part of the glTF export (gltf_export.h).
#pragma once

#include <vector>

#include "assets/scene_assets.h"
#include "export/gltf_buffers.h"

namespace cutaway::gltf {

/// A scene mesh as written: its glTF mesh, the frame its positions need, its coarser levels.
struct AddedMesh {
  int index = -1;
  MeshFrame frame;
  std::vector<int> lods;  ///< glTF meshes of levels 1, 2, ... (names ending _LOD1, _LOD2, ...)
};

/// Adds mesh `mesh` through `out` (one primitive per AssetPrimitive, sharing the vertex
/// attributes; material k of the assets is glTF material gltf_material[k]), and `lods` coarser
/// levels over the same vertices: level l has about 2^-l of each primitive's triangles
/// (simplified(), error at most 2^(l-1) % of the mesh's extent, so a level may keep more).
/// `pivot_at_centroid`: the positions about the mesh's volume_centroid (GltfSceneOptions).
AddedMesh add_asset_mesh(SceneBuffers& out, const AssetMesh& mesh,
                         const std::vector<int>& gltf_material, int lods, bool pivot_at_centroid);

}  // namespace cutaway::gltf
