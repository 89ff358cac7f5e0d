// Grains thinner than a voxel in an interior volume (doc/algorithms.md §8, Grains thinner than
// a voxel): a voxel's one PMVC sample sits at its centre, so a seed that no voxel centre falls
// inside would leave no trace in the volume. Each voxel such a grain passes through takes its
// sample at a point inside the grain instead, and so the grain's own colour.
#pragma once

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "model/ds_model.h"
#include "volume/interior_volume.h"

namespace cutaway {

/// Where the voxels of `grid` that a grain of `model` passes through take their PMVC sample
/// instead of their centre: (voxel index, point inside the grain, metres, object frame), in
/// voxel index order. `solid` (#voxels of grid): whether each voxel is solid; only solid
/// voxels move.
///
/// For each grain (grain_components order), points are laid along its long axis (the line
/// from its centre through its farthest vertex) every half voxel up to its ends; each such
/// point strictly inside the grain moves the voxel whose centre is nearest to it, unless that
/// centre already lies inside one of the grain surface's grains (it shows a grain there) or
/// an earlier point took the voxel. A round grain thus moves the voxel at its centre, and a
/// strand one voxel every voxel of its length. A grain surface that is not closed is skipped.
std::vector<std::pair<size_t, glm::dvec3>> thin_grain_samples(const DsModel& model,
                                                              const InteriorVolume& grid,
                                                              std::span<const char> solid);

}  // namespace cutaway
