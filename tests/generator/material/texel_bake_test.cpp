// Baking helpers (generator/material/texel_bake.h): the pull-push background fill keeps the covered
// texels, fills every other one with a convex mix of them that varies smoothly, and leaves an
// empty canvas alone.
#include "material/texel_bake.h"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace cutaway {
namespace {

/// A 100 x 60 canvas with a red 10 x 10 island at the left and a blue one at the right, the
/// islands with roughness 0.2 and 0.8.
TexelCanvas two_islands() {
  TexelCanvas canvas(100, 60, false);
  for (int y = 25; y < 35; ++y)
    for (int x = 0; x < 10; ++x) {
      const size_t left = static_cast<size_t>(y) * 100 + x, right = left + 90;
      canvas.colour[left] = {1, 0, 0};
      canvas.colour[right] = {0, 0, 1};
      canvas.material[left] = {0.2, 0};
      canvas.material[right] = {0.8, 0};
      canvas.covered[left] = canvas.covered[right] = 1;
    }
  return canvas;
}

TEST(TexelBake, PullPushFillsTheBackgroundSmoothlyFromTheIslands) {
  const TexelCanvas before = two_islands();
  TexelCanvas canvas = before;
  fill_background(canvas);
  double steepest = 0;
  for (int y = 0; y < canvas.height; ++y)
    for (int x = 0; x < canvas.width; ++x) {
      const size_t i = static_cast<size_t>(y) * canvas.width + x;
      if (before.covered[i]) {
        EXPECT_EQ(canvas.colour[i], before.colour[i]);
        EXPECT_EQ(canvas.material[i], before.material[i]);
        continue;
      }
      // A mix of red and blue (no green, no black), roughness between the islands'.
      const glm::dvec3 c = canvas.colour[i];
      EXPECT_NEAR(c.r + c.b, 1.0, 1e-9) << x << ", " << y;
      EXPECT_EQ(c.g, 0.0);
      EXPECT_GE(canvas.material[i].x, 0.2 - 1e-9);
      EXPECT_LE(canvas.material[i].x, 0.8 + 1e-9);
      if (x + 1 < canvas.width)
        steepest = std::max(steepest, glm::distance(c, canvas.colour[i + 1]));
    }
  // Red near the red island, blue near the blue one, a gradient between: no texel-to-texel
  // step above a tenth of the red-to-blue distance (1.41) away from the islands' edges.
  EXPECT_GT(canvas.colour[30 * 100 + 12].r, 0.8);
  EXPECT_GT(canvas.colour[30 * 100 + 87].b, 0.8);
  EXPECT_LT(steepest, 0.15);
  // Deterministic.
  TexelCanvas again = before;
  fill_background(again);
  EXPECT_EQ(again.colour, canvas.colour);
  EXPECT_EQ(again.material, canvas.material);
}

TEST(TexelBake, PullPushLeavesAnEmptyCanvasAlone) {
  TexelCanvas canvas(7, 5, false);
  fill_background(canvas);
  for (const glm::dvec3& c : canvas.colour) EXPECT_EQ(c, glm::dvec3(0.0));
}

TEST(TexelBake, HalfSizeAveragesTwoByTwoTexels) {
  // 5 x 3: the last column and row average fewer texels.
  TexelCanvas canvas(5, 3, false);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      const size_t i = static_cast<size_t>(y) * 5 + x;
      canvas.colour[i] = glm::dvec3(x + 10.0 * y);
      canvas.material[i] = {x, y};
    }
  canvas.covered[1] = 1;  // (1, 0)
  const TexelCanvas half = half_size(canvas);
  ASSERT_EQ(half.width, 3);
  ASSERT_EQ(half.height, 2);
  EXPECT_EQ(half.colour[0], glm::dvec3((0 + 1 + 10 + 11) / 4.0));
  EXPECT_EQ(half.colour[2], glm::dvec3((4 + 14) / 2.0));   // column 4 alone
  EXPECT_EQ(half.colour[3], glm::dvec3((20 + 21) / 2.0));  // row 2 alone
  EXPECT_EQ(half.colour[5], glm::dvec3(24.0));             // the corner texel alone
  EXPECT_EQ(half.material[4], glm::dvec2(2.5, 2.0));
  EXPECT_EQ(half.covered, (HugePageVector<uint8_t>{1, 0, 0, 0, 0, 0}));
}

}  // namespace
}  // namespace cutaway
