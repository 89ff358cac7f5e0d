#include "base/colour.h"

#include <gtest/gtest.h>

namespace cutaway {
namespace {

TEST(Colour, SrgbRoundTripAndKnownValues) {
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgb_to_linear(1.0), 1.0);
  EXPECT_NEAR(srgb_to_linear(0.5), 0.2140, 1e-4);  // IEC 61966-2-1
  for (double c = 0; c <= 1.0; c += 0.01) EXPECT_NEAR(linear_to_srgb(srgb_to_linear(c)), c, 1e-12);
}

}  // namespace
}  // namespace cutaway
