#include "volume/volume_cost.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include <glm/common.hpp>

namespace cutaway {

glm::dvec3 grid_voxels(const glm::dvec3& extent, double voxel_m) {
  // The box's voxels, plus one empty voxel beyond it on each side.
  return glm::ceil(extent / voxel_m) + 3.0;
}

Check check_volume_rays(double voxels, int cube) {
  const double rays = volume_rays(voxels, cube);
  if (rays <= kMaxVolumeRays) return {};
  char text[200];
  std::snprintf(text, sizeof text,
                "the volume would cast about %.3g rays (%.3g voxels x %.0f rays each at cube "
                "%d), more than the %.3g any volume may cost",
                rays, voxels, volume_rays(1, cube), cube, kMaxVolumeRays);
  return Check::none(text);
}

int most_voxels_across(const glm::dvec3& extent, int cube) {
  const double longest = std::max({extent.x, extent.y, extent.z});
  const auto fits = [&](int across) {
    const glm::dvec3 n = grid_voxels(extent, longest / across);
    const double voxels = n.x * n.y * n.z;
    return voxels <= static_cast<double>(kMaxVolumeVoxels) && check_volume_rays(voxels, cube);
  };
  // The grid grows with `across`, and 1,000 across is beyond both bounds at every cube size.
  int lo = 0, hi = 1000;  // fits(lo) (or lo == 0), !fits(hi)
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace cutaway
