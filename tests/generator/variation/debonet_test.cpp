// De Bonet synthesis on cyclic signals and section loops (generator/variation/debonet.h).
#include "base/constants.h"
#include "variation/debonet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <glm/geometric.hpp>

namespace cutaway {
namespace {

/// A textured 2-channel cyclic signal: a few incommensurate bumps plus pseudo-random detail.
CyclicSignal texture(int n) {
  CyclicSignal s(n, 2);
  Rng r(derive_seed(5, {}));
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * i / n;
    s.at(i, 0) = 1.0 + 0.1 * std::sin(3 * t) + 0.05 * std::sin(11 * t + 1) + 0.02 * r.uniform();
    s.at(i, 1) = 2 * kPi / n * (1 + 0.2 * std::cos(5 * t) + 0.05 * r.uniform());
  }
  return s;
}

double mean_abs_diff(const CyclicSignal& a, const CyclicSignal& b, int c) {
  double s = 0;
  for (int i = 0; i < a.length; ++i) s += std::abs(a.at(i, c) - b.at(i, c));
  return s / a.length;
}

TEST(DeBonet, PyramidCollapsesToTheInput) {
  const CyclicSignal s = texture(128);
  const auto bands = laplacian_pyramid(s, 8);
  ASSERT_EQ(bands.size(), 5u);  // 128 64 32 16 8
  EXPECT_EQ(bands.back().length, 8);
  const CyclicSignal c = collapse_pyramid(bands);
  for (size_t k = 0; k < s.v.size(); ++k) EXPECT_NEAR(c.v[k], s.v[k], 1e-12);
}

TEST(DeBonet, AmountZeroReproducesTheInput) {
  const CyclicSignal s = texture(128);
  DeBonetOptions opt;
  opt.amount = 0;
  for (uint64_t seed : {1u, 2u, 3u}) {
    Rng rng(seed);
    const CyclicSignal o = debonet_synthesize(s, opt, rng);
    for (size_t k = 0; k < s.v.size(); ++k) ASSERT_NEAR(o.v[k], s.v[k], 1e-12);
  }
}

TEST(DeBonet, LargerAmountVariesMore) {
  const CyclicSignal s = texture(128);
  double previous = 0;
  for (double amount : {0.0, 0.5, 2.0}) {
    DeBonetOptions opt;
    opt.amount = amount;
    double stat = 0;
    for (uint64_t seed = 0; seed < 20; ++seed) {
      Rng rng(derive_seed(seed, {1}));
      stat += mean_abs_diff(debonet_synthesize(s, opt, rng), s, 0) / 20;
    }
    if (amount == 0) {
      EXPECT_LT(stat, 1e-12);
    } else {
      EXPECT_GT(stat, previous * 1.2) << "amount " << amount;
    }
    previous = stat;
  }
}

TEST(DeBonet, BandValuesAreTheInputs) {
  const CyclicSignal s = texture(128);
  const auto in = laplacian_pyramid(s, 8);
  Rng rng(derive_seed(7, {}));
  DeBonetOptions opt;
  opt.amount = 3;
  const auto out = synthesize_bands(in, opt, rng);
  ASSERT_EQ(out.size(), in.size());
  bool changed = false;
  for (size_t l = 0; l < in.size(); ++l) {
    for (int c = 0; c < 2; ++c) {
      std::set<double> values;
      double lo = 1e300, hi = -1e300;
      for (int i = 0; i < in[l].length; ++i) {
        values.insert(in[l].at(i, c));
        lo = std::min(lo, in[l].at(i, c));
        hi = std::max(hi, in[l].at(i, c));
      }
      for (int i = 0; i < out[l].length; ++i) {
        EXPECT_TRUE(values.count(out[l].at(i, c))) << "level " << l;
        EXPECT_GE(out[l].at(i, c), lo);
        EXPECT_LE(out[l].at(i, c), hi);
        changed |= out[l].at(i, c) != in[l].at(i, c);
      }
    }
  }
  EXPECT_TRUE(changed);
}

Polyline2 bumpy_loop(double radius, int bumps) {
  Polyline2 loop;
  for (int i = 0; i < 36; ++i) {
    const double a = 2 * kPi * i / 36;
    const double r = radius * (1 + 0.04 * std::sin(bumps * a) + 0.02 * std::cos(7 * a + 0.3));
    loop.push_back({r * std::cos(a), -r * std::sin(a)});
  }
  return loop;
}

TEST(DeBonet, PolarLoopRoundTrip) {
  const Polyline2 loop = bumpy_loop(0.04, 3);
  const PolarLoop p = polar_resample(loop, true, 64);
  double sum = 0;
  for (double d : p.dphi) {
    EXPECT_GT(d, 0);
    sum += d;
  }
  EXPECT_NEAR(sum, 2 * kPi, 1e-9);
  const Polyline2 back = loop_from_polar(p);
  ASSERT_EQ(back.size(), 64u);
  EXPECT_NEAR(back[0].y, 0, 1e-15);  // starts at angle 0
  // Same points as the uniform resampling (angles re-normalised: tiny drift only).
  const PolarLoop q = polar_resample(back, false, 64);
  for (int i = 0; i < 64; ++i) EXPECT_NEAR(q.rho[i], p.rho[i], 1e-4 * 0.04);
}

TEST(DeBonet, SeedsGiveDistinctNestedLoops) {
  const std::vector<Polyline2> loops{bumpy_loop(0.04, 5), bumpy_loop(0.03, 5)};
  DeBonetOptions opt;
  Rng a(derive_seed(1, {})), b(derive_seed(2, {})), a2(derive_seed(1, {}));
  const auto la = synthesize_loops(loops, {true, true}, 128, opt, a);
  const auto lb = synthesize_loops(loops, {true, true}, 128, opt, b);
  const auto la2 = synthesize_loops(loops, {true, true}, 128, opt, a2);
  ASSERT_EQ(la.size(), 2u);
  double diff = 0;
  for (size_t i = 0; i < la[0].size(); ++i) {
    diff += glm::distance(la[0][i], lb[0][i]);
    EXPECT_EQ(la[0][i], la2[0][i]);  // same seed, same loop
    // The inner loop stays inside the outer one at the same sample.
    EXPECT_LT(glm::length(la[1][i]), glm::length(la[0][i]));
  }
  EXPECT_GT(diff / la[0].size(), 1e-5);
}

}  // namespace
}  // namespace cutaway
