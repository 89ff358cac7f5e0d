#include "volume/thin_layers.h"

#include <map>

#include "base/error.h"

namespace cutaway {

std::vector<std::pair<size_t, glm::dvec3>> thin_layer_samples(const InteriorVolume& grid,
                                                              std::span<const char> solid,
                                                              std::span<const ThinLayer> layers,
                                                              std::vector<char>& taken) {
  CUTAWAY_CHECK(solid.size() == grid.voxels() && taken.size() == grid.voxels());
  const size_t step[3] = {1, static_cast<size_t>(grid.size.x),
                          static_cast<size_t>(grid.size.x) * grid.size.y};
  std::map<size_t, glm::dvec3> moved;
  for (const ThinLayer& layer : layers) {
    CUTAWAY_CHECK(layer.axis >= 0 && layer.axis < 3 &&
                  grid.voxel(layer.voxel)[layer.axis] + 1 < grid.size[layer.axis]);
    glm::dvec3 at = grid.centre(grid.voxel(layer.voxel));
    at[layer.axis] += layer.middle_m;
    const size_t next = layer.voxel + step[layer.axis];
    const bool nearer_first = layer.middle_m <= 0.5 * grid.voxel_m;
    for (const size_t v : {nearer_first ? layer.voxel : next, nearer_first ? next : layer.voxel}) {
      if (!solid[v] || taken[v]) continue;
      taken[v] = 1;
      moved.emplace(v, at);
      break;
    }
  }
  return {moved.begin(), moved.end()};
}

}  // namespace cutaway
