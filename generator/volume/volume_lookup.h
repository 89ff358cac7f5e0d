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

/// `volume` read at `point` (metres, object frame). Of the 8 voxel centres around the point,
/// with trilinear weights w, each region r present gets the score sum_k w_k s_k d_k, where
/// d_k is voxel k's sheet distance and s_k is +1 when voxel k is in r and -1 otherwise: a
/// signed distance to r's border, interpolated, which is exact for a plane between the
/// centres. The point takes the region with the highest score (ties: the lower id), and the
/// colour and material of that region's voxels only, by their trilinear weights renormalised.
/// So a sheet stays a sharp line at its own place within a voxel instead of a one-voxel
/// blend, and one side's colour never bleeds into the other. Outside the grid: empty.
VolumeSample sample_volume(const InteriorVolume& volume, const glm::dvec3& point);

}  // namespace cutaway
