// AreaSampler (base/area_sampling.h): triangles drawn in proportion to their area, weights
// uniform over the triangle, and the same draws from the same seed.
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "base/area_sampling.h"
#include "base/random.h"

namespace cutaway {
namespace {

TEST(AreaSampler, DrawsTrianglesInProportionToAreaAndWeightsInsideThem) {
  // Areas 1, 0 and 3: a quarter, none, three quarters.
  const AreaSampler sampler({1.0, 0.0, 3.0});
  EXPECT_DOUBLE_EQ(sampler.total(), 4.0);
  Rng rng(derive_seed(5, {1}));
  const size_t n = 40000;
  size_t count[3] = {0, 0, 0};
  double mean_u = 0;
  for (size_t k = 0; k < n; ++k) {
    const AreaSample s = sampler.draw(rng);
    ASSERT_LT(s.triangle, 3u);
    ++count[s.triangle];
    EXPECT_GE(s.weights.x, 0.0);
    EXPECT_GE(s.weights.y, 0.0);
    EXPECT_GE(s.weights.z, 0.0);
    EXPECT_NEAR(s.weights.x + s.weights.y + s.weights.z, 1.0, 1e-12);
    mean_u += s.weights.y / static_cast<double>(n);
  }
  EXPECT_EQ(count[1], 0u);
  // Binomial standard deviation sqrt(n p (1 - p)) = 87 draws; 5 of them allowed.
  EXPECT_NEAR(static_cast<double>(count[0]), 0.25 * n, 450.0);
  // A uniform point in a triangle has mean weight 1/3 at each corner.
  EXPECT_NEAR(mean_u, 1.0 / 3.0, 0.005);
  // The same seed gives the same draws.
  Rng a(derive_seed(5, {2})), b(derive_seed(5, {2}));
  for (int k = 0; k < 100; ++k) {
    const AreaSample x = sampler.draw(a), y = sampler.draw(b);
    EXPECT_EQ(x.triangle, y.triangle);
    EXPECT_EQ(x.weights, y.weights);
  }
}

}  // namespace
}  // namespace cutaway
