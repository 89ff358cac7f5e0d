#include "material/cellular_noise.h"

#include <glm/geometric.hpp>

namespace cutaway {

CellDistances cell_distances(uint64_t cells, const glm::dvec3& q, unsigned period_x) {
  CellDistances d{1e300, 1e300};
  visit_feature_points(cells, q, period_x, [&](const glm::dvec3& point, uint64_t&) {
    const double r = glm::length(q - point);
    if (r < d.f1) {
      d.f2 = d.f1;
      d.f1 = r;
    } else if (r < d.f2) {
      d.f2 = r;
    }
  });
  return d;
}

}  // namespace cutaway
