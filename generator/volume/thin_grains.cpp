#include "volume/thin_grains.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include <glm/geometric.hpp>

#include "base/error.h"
#include "model/grain_components.h"
#include "model/inside_test.h"

namespace cutaway {

std::vector<std::pair<size_t, glm::dvec3>> thin_grain_samples(const DsModel& model,
                                                              const InteriorVolume& grid,
                                                              std::span<const char> solid) {
  CUTAWAY_CHECK(solid.size() == grid.voxels() && grid.voxel_m > 0);
  const std::vector<GrainComponent> grains = grain_components(model);
  // One inside test per closed grain surface (its grains are disjoint closed components, so a
  // point is inside the surface when it is inside one of them).
  std::map<size_t, std::unique_ptr<InsideTest>> tests;
  for (const GrainComponent& grain : grains)
    if (!tests.contains(grain.surface))
      tests[grain.surface] = closed_surface(model.surfaces[grain.surface].mesh)
                                 ? std::make_unique<InsideTest>(model.surfaces[grain.surface].mesh)
                                 : nullptr;
  std::map<size_t, glm::dvec3> moved;
  const double step = 0.5 * grid.voxel_m;
  for (const GrainComponent& grain : grains) {
    const InsideTest* test = tests[grain.surface].get();
    if (!test) continue;
    // The long axis: from the centre to the farthest vertex.
    const double half = grain.radius;
    const glm::dvec3 axis = half > 0 ? (grain.farthest - grain.centre) / half : glm::dvec3(0.0);
    const int steps = static_cast<int>(std::floor(half / step));
    // The centre first, then outwards: +1, -1, +2, -2, ...
    for (int k = 0; k <= 2 * steps; ++k) {
      const int at = (k + 1) / 2 * (k % 2 == 1 ? 1 : -1);
      const glm::dvec3 q = grain.centre + axis * (at * step);
      const glm::dvec3 cell = glm::round((q - grid.origin) / grid.voxel_m);
      if (cell.x < 0 || cell.y < 0 || cell.z < 0 || cell.x >= grid.size.x ||
          cell.y >= grid.size.y || cell.z >= grid.size.z)
        continue;
      const size_t v =
          grid.index(static_cast<int>(cell.x), static_cast<int>(cell.y), static_cast<int>(cell.z));
      if (!solid[v] || moved.contains(v) || !test->inside(q) ||
          test->inside(grid.centre(grid.voxel(v))))
        continue;
      moved.emplace(v, q);
    }
  }
  return {moved.begin(), moved.end()};
}

}  // namespace cutaway
