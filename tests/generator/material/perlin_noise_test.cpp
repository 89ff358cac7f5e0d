// Improved Perlin noise (generator/material/perlin_noise.h): zero on the lattice, bounded by
// kBound, continuous, deterministic per seed and different across seeds, about zero mean.
#include "material/perlin_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/random.h"

namespace cutaway {
namespace {

TEST(PerlinNoise, ZeroAtIntegerLatticePoints) {
  const PerlinNoise noise(7);
  for (int x = -300; x <= 300; x += 13) {
    for (int y = -5; y <= 5; ++y) {
      for (int z = -3; z <= 260; z += 29) {
        EXPECT_EQ(noise({x, y, z}), 0.0) << x << " " << y << " " << z;
      }
    }
  }
}

TEST(PerlinNoise, BoundedAndNotDegenerate) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    const PerlinNoise noise(seed);
    Rng rng(derive_seed(99, {seed}));
    double lo = 0, hi = 0, sum2 = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const glm::dvec3 p{rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50)};
      const double v = noise(p);
      ASSERT_LE(std::fabs(v), PerlinNoise::kBound) << p.x << " " << p.y << " " << p.z;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      sum2 += v * v;
    }
    // Uses most of its range; the standard deviation the header documents (about 0.27).
    EXPECT_LT(lo, -0.6);
    EXPECT_GT(hi, 0.6);
    const double sd = std::sqrt(sum2 / n);
    EXPECT_GT(sd, 0.22);
    EXPECT_LT(sd, 0.32);
  }
}

TEST(PerlinNoise, ContinuousAcrossCellFaces) {
  const PerlinNoise noise(11);
  Rng rng(5);
  for (int i = 0; i < 2000; ++i) {
    // A point on a cell face (x integer) and its neighbours just either side.
    const glm::dvec3 p{std::floor(rng.uniform(-20, 20)), rng.uniform(-20, 20),
                       rng.uniform(-20, 20)};
    const double h = 1e-7;
    EXPECT_NEAR(noise(p + glm::dvec3(h, 0, 0)), noise(p - glm::dvec3(h, 0, 0)), 1e-6);
    // Lipschitz: the gradient is bounded (a few units), so small steps give small changes.
    const glm::dvec3 q{rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-20, 20)};
    const double step = 1e-3;
    EXPECT_LT(std::fabs(noise(q + glm::dvec3(step, step, step)) - noise(q)), 10 * step);
  }
}

TEST(PerlinNoise, DeterministicPerSeedAndDifferentAcrossSeeds) {
  const PerlinNoise a(42), b(42), c(43);
  EXPECT_EQ(a.permutation(), b.permutation());
  EXPECT_NE(a.permutation(), c.permutation());
  // The table is a permutation of 0..255.
  std::vector<int> seen(256, 0);
  for (uint8_t v : a.permutation()) ++seen[v];
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 256);

  Rng rng(3);
  int differ = 0;
  for (int i = 0; i < 1000; ++i) {
    const glm::dvec3 p{rng.uniform(-9, 9), rng.uniform(-9, 9), rng.uniform(-9, 9)};
    EXPECT_EQ(a(p), b(p));
    differ += std::fabs(a(p) - c(p)) > 1e-3;
  }
  EXPECT_GT(differ, 900);
}

TEST(PerlinNoise, GoldenValues) {
  // Catches any change of the permutation, gradients or fade (across platforms too).
  const PerlinNoise noise(derive_seed(2024, {1}));
  EXPECT_NEAR(noise({0.5, 0.5, 0.5}), 0.375, 1e-15);
  EXPECT_NEAR(noise({-3.25, 17.8, 101.01}), -0.030390315381468098, 1e-15);
  EXPECT_NEAR(noise({1e3 + 0.3, -7.7, 0.125}), 0.13565431245054632, 1e-15);
}

TEST(PerlinNoise, PeriodicWith256) {
  const PerlinNoise noise(8);
  Rng rng(4);
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 p{rng.uniform(0, 10), rng.uniform(0, 10), rng.uniform(0, 10)};
    EXPECT_NEAR(noise(p), noise(p + glm::dvec3(256, -512, 0)), 1e-9);
  }
}

TEST(PerlinNoise, ZeroMeanOverALargeBox) {
  const PerlinNoise noise(12345);
  // A regular grid off the lattice over 64^3 cells: the mean is close to 0 next to the
  // standard deviation (about 0.27).
  double sum = 0;
  int n = 0;
  for (double x = 0.37; x < 64; x += 0.71) {
    for (double y = 0.11; y < 64; y += 0.83) {
      for (double z = 0.53; z < 64; z += 0.97) {
        sum += noise({x, y, z});
        ++n;
      }
    }
  }
  EXPECT_LT(std::fabs(sum / n), 0.01) << "mean " << sum / n << " over " << n;
}

TEST(PerlinNoise, PeriodicAlongXWrapsWithoutASeamAndEqualsThePlainNoiseAt256) {
  const PerlinNoise noise(77);
  Rng rng(3);
  for (int i = 0; i < 500; ++i) {
    const glm::dvec3 p(rng.uniform(-300, 300), rng.uniform(-50, 50), rng.uniform(-50, 50));
    EXPECT_EQ(noise.periodic(p, 256), noise(p));
    for (unsigned period : {1u, 7u, 52u, 255u}) {
      EXPECT_NEAR(noise.periodic(p + glm::dvec3(period, 0, 0), period), noise.periodic(p, period),
                  1e-9);
      // Continuous across the wrap: just below a multiple of the period and just above it.
      const glm::dvec3 w(period * std::floor(p.x / period), p.y, p.z);
      EXPECT_NEAR(noise.periodic(w - glm::dvec3(1e-9, 0, 0), period),
                  noise.periodic(w + glm::dvec3(1e-9, 0, 0), period), 1e-6);
    }
  }
}

}  // namespace
}  // namespace cutaway
