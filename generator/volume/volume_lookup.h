// Reading an interior volume at any point, keeping sheets crisp between the samples
// (doc/algorithms.md §8, Reading the volume): the rule the cutting page's shader follows, in
// C++ for the accuracy table and the tests.
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "volume/interior_volume.h"

namespace cutaway {

/// What a volume says at one point.
struct VolumeSample {
  uint32_t region = kEmptyRegion;  ///< kEmptyRegion: outside the object or in a cavity
  glm::vec3 colour{0.0f};          ///< linear RGB (0 where empty)
  glm::vec2 material{0.0f};        ///< roughness, translucency (0 where empty)
};

/// `volume` read at `point` (metres, object frame), from the 8 voxel centres around the point
/// with trilinear weights w:
/// 1. Solid or empty: the score sum_k w_k s_k e_k, where e_k is voxel k's outline distance
///    and s_k is +1 when voxel k is solid and -1 when empty: a signed distance to the outline,
///    interpolated (exact for a plane between the centres). Not above 0: empty.
/// 2. Which solid region: each solid region r among the 8 gets sum_k w_k s_k d_k, with d_k
///    the sheet distance and s_k +1 when voxel k is in r, else -1; the highest wins (ties: the
///    lower id).
/// 3. The colour and material of that region's voxels only, by their trilinear weights
///    renormalised.
/// So a sheet stays a sharp line at its own place within a voxel instead of a one-voxel blend,
/// one side's colour never bleeds into the other, and the outline stays where the skin is
/// even when a layer thinner than a voxel lies under it. Outside the grid: empty.
VolumeSample sample_volume(const InteriorVolume& volume, const glm::dvec3& point);

}  // namespace cutaway
