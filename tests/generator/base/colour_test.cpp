#include "base/colour.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "base/random.h"

namespace cutaway {
namespace {

TEST(Colour, SrgbRoundTripAndKnownValues) {
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgb_to_linear(1.0), 1.0);
  EXPECT_NEAR(srgb_to_linear(0.5), 0.2140, 1e-4);  // IEC 61966-2-1
  for (double c = 0; c <= 1.0; c += 0.01) EXPECT_NEAR(linear_to_srgb(srgb_to_linear(c)), c, 1e-12);
}

/// What linear_to_srgb8 must equal: the formula itself.
int srgb8_by_formula(double c) {
  c = std::clamp(c, 0.0, 1.0);
  const double srgb = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<int>(std::lround(255.0 * srgb));
}

// The table gives the formula's bits: everywhere a code can change (4,000 doubles around every
// step, where an error of the last bit of pow() could matter), at the ends, and at random.
// linear_to_srgb takes its power without pow(): within 4 ulp of pow(c, 1 / 2.4) over the whole
// range; input above 1 is clamped.
TEST(Colour, LinearToSrgbAgreesWithPow) {
  Rng rng(2024);
  double worst_ulp = 0;
  for (int i = 0; i < 200000; ++i) {
    const double c = i == 0 ? 0.0031309 : rng.uniform(0.0031309, 1.0);
    const double expected = 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    const double power = (linear_to_srgb(c) + 0.055) / 1.055;
    worst_ulp = std::max(worst_ulp, std::abs(power - std::pow(c, 1.0 / 2.4)) /
                                        (std::pow(c, 1.0 / 2.4) * 0x1p-52));
    EXPECT_NEAR(linear_to_srgb(c), expected, 1e-15) << c;
  }
  EXPECT_LT(worst_ulp, 4.0);
  EXPECT_NEAR(linear_to_srgb(1.0), 1.0, 1e-15);
  EXPECT_EQ(linear_to_srgb(2.0), linear_to_srgb(1.0));
}

TEST(Colour, Srgb8TableEqualsTheFormula) {
  for (int k = 1; k <= 255; ++k) {
    // The linear value half a code below step k, by the inverse transfer function.
    const double near = srgb_to_linear((k - 0.5) / 255.0);
    const uint64_t bits = std::bit_cast<uint64_t>(near);
    for (uint64_t b = bits - 2000; b <= bits + 2000; ++b) {
      const double c = std::bit_cast<double>(b);
      ASSERT_EQ(linear_to_srgb8(c), srgb8_by_formula(c)) << "code " << k << ", c = " << c;
    }
    EXPECT_EQ(linear_to_srgb8(near * (1 + 1e-9)), k);
  }
  for (double c : {-1.0, -0.0, 0.0, 1e-300, 0.0031308, 0.5, 1.0, 2.0, 1e300,
                   std::numeric_limits<double>::infinity()})
    EXPECT_EQ(linear_to_srgb8(c), srgb8_by_formula(c)) << c;
  EXPECT_EQ(linear_to_srgb8(std::numeric_limits<double>::quiet_NaN()), 0);
  Rng rng(7);
  for (int i = 0; i < 200000; ++i) {
    const double c = rng.uniform(-0.1, 1.1);
    ASSERT_EQ(linear_to_srgb8(c), srgb8_by_formula(c)) << c;
  }
}

}  // namespace
}  // namespace cutaway
