// What sampling an interior volume costs, counted before any work (doc/interior-volume.md,
// Cost): the voxels of a grid, the rays it casts (its voxels times the rays of each), and the
// bound every accepted volume keeps (`cutaway volume`, batch volumes, the editor's cutting
// page), so that the largest one finishes in minutes on two cores, as the default grid does.
#pragma once

#include <cstddef>

#include <glm/vec3.hpp>

#include "base/outcome.h"
#include "volume/interior_volume.h"

namespace cutaway {

/// The voxels along x, y and z of a grid with voxel edge `voxel_m` over a box of edges `extent`
/// (both metres, positive): each edge's voxels and one empty voxel beyond it on each side, as
/// volume_grid lays its grid over the skin's box. Doubles: a tiny voxel may give counts beyond
/// any integer type.
glm::dvec3 grid_voxels(const glm::dvec3& extent, double voxel_m);

/// Rays sample_interior_volume casts from each voxel centre to classify it, at most: 15 against
/// every surface (the six face-neighbour directions and the kSideVotes votes), 6 against the
/// walls, and 3 looking past a crossing for a thin layer's second sheet (+x, +y, +z).
inline constexpr int kClassifyRaysPerVoxel = 24;

/// The rays a volume of `voxels` voxels casts with PMVC cube-map size `cube`, counted as
/// voxels x (kClassifyRaysPerVoxel + 6 cube^2): every voxel a PMVC point casting every texel
/// of its cube. An upper bound in practice: a quarter to two thirds of a shipped template's
/// voxels are solid (the PMVC points), and adaptive directions (the default) cast about 40 %
/// of the cube.
constexpr double volume_rays(double voxels, int cube) {
  return voxels * (kClassifyRaysPerVoxel + 6.0 * cube * cube);
}

/// The cube size the volume budget is counted at: 16, the default cube when the bound was set.
/// Kept when the default became 12 (diffusion.h), so that the budget stays the same number of
/// rays: at cube 12 the same grid costs 57 % of it.
inline constexpr int kBudgetCubeSize = 16;

/// The most rays a volume may cost: the default grid (kDefaultVoxelsAcross along the longest
/// edge) over a cube-shaped box, kDefaultVoxelsAcross + 4 voxels a side (the most that grid
/// has, rounding included), at kBudgetCubeSize: about 1.56e9. So the default volume of every
/// template is accepted, and no accepted volume costs more than the roundest templates'
/// defaults at cube 16 (39 to 347 s of PMVC on two cores, doc/interior-volume.md). The leek's
/// largest accepted volume (0.99 million voxels of 0.628 mm, 1.54e9 rays counted) cast 0.40e9
/// and took 198 processor seconds.
inline constexpr double kMaxVolumeRays = volume_rays(
    double{kDefaultVoxelsAcross + 4} * (kDefaultVoxelsAcross + 4) * (kDefaultVoxelsAcross + 4),
    kBudgetCubeSize);

/// Passes when a volume of `voxels` voxels at cube size `cube` costs at most kMaxVolumeRays
/// (volume_rays), else fails with "the volume would cast about R rays (V voxels x P rays
/// each at cube C), more than the M any volume may cost"; the caller adds how to get under it.
Check check_volume_rays(double voxels, int cube);

/// The most voxels along the longest edge of a box of edges `extent` (metres, positive) whose
/// grid (grid_voxels, with the voxel edge the longest edge / N) has at most kMaxVolumeVoxels
/// voxels and passes check_volume_rays at cube size `cube`; 0 when not even 1 does.
int most_voxels_across(const glm::dvec3& extent, int cube);

}  // namespace cutaway
