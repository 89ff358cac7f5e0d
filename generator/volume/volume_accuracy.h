// How well an interior volume reproduces PMVC on cuts it was not made for (doc/algorithms.md
// §8, Accuracy): the table that chose the default voxel size, and the tests' bound.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/plane.h"
#include "diffusion/diffusion.h"
#include "model/ds_model.h"
#include "volume/interior_volume.h"

namespace cutaway {

/// Colour errors of a volume against PMVC, in steps of 1/255 of sRGB (colour_difference).
struct VolumeErrors {
  size_t points = 0;                   ///< solid cap points compared
  size_t near_points = 0;              ///< of them, within one voxel of a surface along an axis
  double mean_far = 0, p99_far = 0;    ///< at points more than one voxel from every surface
  double mean_near = 0, p99_near = 0;  ///< at points within one voxel of a surface
  /// Share of the cap points (solid by classify_points, or by the volume) whose solid or
  /// empty the volume gets wrong: the outline's error.
  double wrong_side = 0;
};

/// `count` planes through the middle of `model`'s skin: each through a point uniform in the
/// middle half of the skin's bounding box, with a direction uniform on the sphere, from a
/// pcg32 stream of `seed`.
std::vector<Plane> random_cap_planes(const DsModel& model, int count, uint64_t seed);

/// Compares `volume` (sample_volume) with `diffusion` (PMVC, the cut faces' colours) on the
/// caps of `planes`: at the points of a square lattice of spacing voxel_m / 2 on each plane
/// within the volume's grid, the lattice turned and shifted by an irrational step so that it
/// does not line up with the voxels. Colours without Perlin modulation on both sides.
VolumeErrors volume_errors(const DsModel& model, const DiffusionBackend& diffusion,
                           const InteriorVolume& volume, const std::vector<Plane>& planes,
                           int threads = 0);

}  // namespace cutaway
