// Deterministic random numbers (generator/base/random.h): golden values catch any change of
// platform, compiler or library; moments check the transforms.
#include "base/random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace cutaway {
namespace {

TEST(Random, Pcg32MatchesTheReferenceDemo) {
  // pcg32-demo of the PCG reference implementation: seed 42, stream 54.
  pcg32 g(42u, 54u);
  const uint32_t expected[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u};
  for (uint32_t e : expected) EXPECT_EQ(g(), e);
}

TEST(Random, GoldenValues) {
  EXPECT_EQ(derive_seed(42, {}), 0xbdd732262feb6e95ULL);
  EXPECT_EQ(derive_seed(42, {1, 2, 3}), 0x04cc9177d1411df4ULL);
  Rng r(derive_seed(42, {7}));
  EXPECT_EQ(r.next_u32(), 3636359614u);
  EXPECT_EQ(r.next_u32(), 377413883u);
  EXPECT_EQ(r.next_u32(), 2936231114u);
  EXPECT_EQ(r.uniform(), 0.28907646279152222);
  EXPECT_EQ(r.uniform(), 0.023889614996473685);
  EXPECT_EQ(r.uniform(), 0.12420150734059676);
  EXPECT_NEAR(r.normal(), 1.1756380365113375, 1e-15);
  EXPECT_NEAR(r.normal(), -0.8185400608085498, 1e-15);
  EXPECT_NEAR(r.normal(), 0.81778709147806317, 1e-15);
  EXPECT_EQ(r.below(10), 3u);
  EXPECT_EQ(r.below(10), 7u);
  EXPECT_EQ(r.below(10), 4u);
}

TEST(Random, PathsGiveDistinctSeeds) {
  EXPECT_NE(derive_seed(1, {2, 3}), derive_seed(1, {3, 2}));
  EXPECT_NE(derive_seed(1, {0}), derive_seed(1, {}));
  EXPECT_NE(derive_seed(1, {0}), derive_seed(2, {0}));
  EXPECT_EQ(derive_seed(9, {4, 5}), derive_seed(9, {4, 5}));
}

TEST(Random, UniformAndNormalMoments) {
  Rng r(derive_seed(123, {}));
  const int n = 200000;
  double s = 0, s2 = 0, lo = 1, hi = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    s += u;
    s2 += u * u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_NEAR(s / n, 0.5, 0.005);
  EXPECT_NEAR(s2 / n - (s / n) * (s / n), 1.0 / 12, 0.002);
  EXPECT_LT(lo, 1e-3);
  EXPECT_GT(hi, 1 - 1e-3);
  s = s2 = 0;
  double s4 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal();
    s += x;
    s2 += x * x;
    s4 += x * x * x * x;
  }
  EXPECT_NEAR(s / n, 0.0, 0.01);
  EXPECT_NEAR(s2 / n, 1.0, 0.02);
  EXPECT_NEAR(s4 / n, 3.0, 0.1);
  std::vector<int> hist(7, 0);
  for (int i = 0; i < 70000; ++i) ++hist[r.below(7)];
  for (int h : hist) EXPECT_NEAR(h, 10000, 400);
  EXPECT_NEAR(r.uniform(2.0, 3.0), 2.5, 0.5);
}

}  // namespace
}  // namespace cutaway
