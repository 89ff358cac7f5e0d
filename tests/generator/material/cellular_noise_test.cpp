// Worley's cellular basis (generator/material/cellular_noise.h): F1 <= F2, F1 is the distance to
// the nearest feature point (checked against a wider search), the wrapped lattice repeats with
// its period, and the same seed gives the same points.
#include "material/cellular_noise.h"

#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "base/random.h"

namespace cutaway {
namespace {

/// F1 by brute force over the 5 x 5 x 5 cells around q.
double nearest_by_wide_search(uint64_t cells, const glm::dvec3& q, unsigned period_x) {
  double best = 1e300;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz)
        visit_feature_points(cells, q + glm::dvec3(dx, dy, dz), period_x,
                             [&](const glm::dvec3& point, uint64_t&) {
                               best = std::min(best, glm::length(q - point));
                             });
  return best;
}

TEST(CellularNoise, NearestDistanceIsExactAndTheSecondIsNotNearer) {
  Rng rng(8);
  for (int i = 0; i < 300; ++i) {
    const glm::dvec3 q(rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(-40, 40));
    for (unsigned period : {0u, 9u}) {
      const CellDistances d = cell_distances(1234, q, period);
      EXPECT_LE(d.f1, d.f2);
      EXPECT_LT(d.f2, 1e300);
      EXPECT_DOUBLE_EQ(d.f1, nearest_by_wide_search(1234, q, period));
    }
  }
}

TEST(CellularNoise, AWrappedLatticeRepeatsWithItsPeriodAndSeedsDiffer) {
  Rng rng(2);
  for (int i = 0; i < 300; ++i) {
    const glm::dvec3 q(rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(-40, 40));
    const CellDistances a = cell_distances(55, q, 12);
    const CellDistances b = cell_distances(55, q + glm::dvec3(12, 0, 0), 12);
    EXPECT_NEAR(a.f1, b.f1, 1e-9);
    EXPECT_NEAR(a.f2, b.f2, 1e-9);
  }
  int same = 0;
  for (int i = 0; i < 100; ++i) {
    const glm::dvec3 q(0.37 * i, 0.11 * i, -0.23 * i);
    same += cell_distances(1, q, 0).f1 == cell_distances(2, q, 0).f1;
  }
  EXPECT_LT(same, 5);
}

}  // namespace
}  // namespace cutaway
