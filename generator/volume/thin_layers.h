// Layers thinner than a voxel in an interior volume (doc/algorithms.md §8, Layers thinner than
// a voxel): a peel, a rind, a shell or a membrane that falls between two voxel centres of a grid
// line shows nowhere on that line. One of the two voxels then takes its sample in the layer's
// middle, and so the layer's colour.
#pragma once

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "volume/interior_volume.h"

namespace cutaway {

/// A solid layer found on a grid line: going from the centre of `voxel` along +x, +y or +z
/// (`axis` 0, 1, 2), the ray crosses the layer's two sharp sheets before the next centre.
struct ThinLayer {
  size_t voxel = 0;
  int axis = 0;
  double middle_m = 0;  ///< from the voxel's centre along the axis to the layer's middle, metres
};

/// Which voxels of `grid` sample inside `layers` (in voxel, then axis order) instead of at their
/// centres: (voxel index, the layer's middle on the grid line, metres, object frame), in voxel
/// index order. Of the two voxels of a layer's grid line, the one nearer the layer takes it
/// (the first on a tie), or the other where that one is empty (`solid`: per voxel) or `taken`
/// (per voxel: already sampled elsewhere, a grain's; updated); a layer whose two voxels are both
/// empty or taken is skipped. @pre every layer's voxel has a neighbour along its axis
std::vector<std::pair<size_t, glm::dvec3>> thin_layer_samples(const InteriorVolume& grid,
                                                              std::span<const char> solid,
                                                              std::span<const ThinLayer> layers,
                                                              std::vector<char>& taken);

}  // namespace cutaway
