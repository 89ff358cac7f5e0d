// What a cut cache entry must be before a scene uses it (doc/command-line.md, The cut cache):
// an entry is untrusted input, however valid its CRC-32 (an integrity check, not proof of where
// it came from), so every decoded cut object and every set of placements is checked against
// the rules its consumers rely on and against the scene that asked for it. An entry that fails
// is discarded (CutCache::discard) and made again.
#pragma once

#include <cstddef>

#include "assets/scene_assets.h"
#include "base/outcome.h"
#include "cut/object_cut.h"
#include "model/template.h"
#include "placement/collision_shape.h"
#include "placement/container.h"
#include "placement/physics_settle.h"

namespace cutaway {

/// How far from its origin (the base centre of its axis) any part of a variant of `tmpl` may
/// reach, metres: twice (and the variation amount times, where it is over 1) the sum of the
/// largest distance from the origin of any point written
/// in the template (profile points at the section's widest, mesh vertices), of the spine's
/// farthest point and of the largest grain's depth and semi-axis, which leaves room for the
/// variants' synthesis and the spine's bend, plus the organic deformation's reach
/// (organic_reach_m at that amount).
double template_reach_m(const Template& tmpl);

/// Whether the cut object `pieces` and `collision` (one shape per piece, or none when
/// `collision_expected` is false), decoded from an entry into `assets` (with the textures and
/// materials it added, and no meshes), can be used by a scene (else what is wrong, in words).
/// The pieces' meshes are moved into assets.meshes while check_assets looks at them and moved
/// back, so both are left as they were. The rules:
///  - check_assets of `assets` (textures, materials, meshes: sizes, finite values, indices);
///  - as many shapes, infos, cap normals and cut-face counts as meshes;
///  - each shape (ShadedMesh): #V normals, colours and material channels, #V or no params,
///    finite values, triangle indices below #V, at least one triangle;
///  - every position of meshes, shapes and collision corners within `reach_m` of the origin,
///    and each mesh's bounding box the same as its shape's (the same piece, within 1 µm);
///  - finite cap normals, piece volumes >= 0, cut faces >= 0;
///  - collision shapes: at least one part, each of >= 4 finite corners, finite mass properties.
Check check_cached_cut(CutPieces& pieces, const std::vector<CollisionShape>& collision,
                       bool collision_expected, SceneAssets& assets, double reach_m);

/// Whether placements read back from an entry can be used for a scene of `bodies` pieces in
/// `container` (else what is wrong): one placement per piece, finite unit rotations (within
/// 1e-6), finite translations within the container's reach: horizontally within its half size
/// (or `none_radius_m` on the floor) plus 1 m, vertically within 1 m below its base and its
/// height plus 2 m above.
Check check_cached_placements(const std::vector<Placement>& placements, size_t bodies,
                              const Container& container, double none_radius_m);

}  // namespace cutaway
