// Skin relief maps (generator/material/relief_map.h): a ramp of known slope gives the normal of
// that slope, tilted the documented way (X across the texture, Y up it); the height map spans
// the relief's range; slopes wrap across the seam of a repeating texture and stop at an island's
// edge; the background is filled.
#include "material/relief_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "base/error.h"

namespace cutaway {
namespace {

/// A fully covered w x h canvas whose relief is height(x, y) with `metres` per texel both ways.
template <class Height>
TexelCanvas relief_canvas(int w, int h, bool wrap, double metres, Height height) {
  TexelCanvas canvas(w, h, wrap);
  canvas.relief.assign(canvas.covered.size(), glm::dvec3(0.0));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      canvas.covered[i] = 1;
      canvas.relief[i] = {height(x, y), metres, metres};
    }
  return canvas;
}

/// The normal stored at texel (x, y), decoded to -1..1.
glm::dvec3 normal_at(const ReliefMaps& maps, int w, int x, int y) {
  const size_t i = 3 * (static_cast<size_t>(y) * w + x);
  return glm::dvec3(maps.normal[i], maps.normal[i + 1], maps.normal[i + 2]) / 127.5 - 1.0;
}

TEST(ReliefMap, ARampGivesTheNormalOfItsSlopeTiltedAcrossAndUpTheTexture) {
  const double metres = 5e-4;
  // Rising toward +x by half a texel's width per texel: slope 0.5, so the normal leans to -X.
  const ReliefMaps across = bake_relief_maps(
      relief_canvas(16, 16, false, metres, [&](int x, int) { return 0.5 * metres * x; }), 2);
  const glm::dvec3 want = glm::normalize(glm::dvec3(-0.5, 0, 1));
  for (int x : {0, 7, 15}) {
    const glm::dvec3 n = normal_at(across, 16, x, 8);
    EXPECT_NEAR(n.x, want.x, 0.01) << x;
    EXPECT_NEAR(n.y, 0.0, 0.01) << x;
    EXPECT_NEAR(n.z, want.z, 0.01) << x;
  }
  EXPECT_NEAR(across.low_m, 0.0, 1e-12);
  EXPECT_NEAR(across.high_m, 7.5 * metres, 1e-12);
  EXPECT_NEAR(across.texel_m, metres, 1e-15);
  EXPECT_EQ(across.height[8 * 16 + 0], 0);
  EXPECT_EQ(across.height[8 * 16 + 15], 255);
  // Rising toward the top row (y decreasing): the texture's "up", so the normal leans to -Y.
  const ReliefMaps up = bake_relief_maps(
      relief_canvas(16, 16, false, metres, [&](int, int y) { return -0.5 * metres * y; }), 2);
  const glm::dvec3 n = normal_at(up, 16, 8, 8);
  EXPECT_NEAR(n.x, 0.0, 0.01);
  EXPECT_NEAR(n.y, -0.5 / std::sqrt(1.25), 0.01);
}

TEST(ReliefMap, SlopesWrapAcrossTheSeamAndStopAtAnIslandsEdge) {
  const double metres = 1e-3;
  // A bump at column 0 of a repeating texture: the last column rises toward it across the seam.
  const ReliefMaps wrapped = bake_relief_maps(
      relief_canvas(8, 4, true, metres, [&](int x, int) { return x == 0 ? metres : 0.0; }), 1);
  EXPECT_LT(normal_at(wrapped, 8, 7, 2).x, -0.2);  // rising toward +x (the seam)
  EXPECT_GT(normal_at(wrapped, 8, 1, 2).x, 0.2);   // falling toward +x
  const ReliefMaps clamped = bake_relief_maps(
      relief_canvas(8, 4, false, metres, [&](int x, int) { return x == 0 ? metres : 0.0; }), 1);
  EXPECT_NEAR(normal_at(clamped, 8, 7, 2).x, 0.0, 0.01);
  // An island: the covered texel beside uncovered ones takes a one-sided slope, and the
  // uncovered texels are filled with flat-ish normals (no black, no garbage).
  TexelCanvas island =
      relief_canvas(8, 8, false, metres, [&](int x, int) { return 0.25 * metres * x; });
  for (int y = 0; y < 8; ++y)
    for (int x = 4; x < 8; ++x) island.covered[static_cast<size_t>(y) * 8 + x] = 0;
  const ReliefMaps maps = bake_relief_maps(island, 1);
  EXPECT_NEAR(normal_at(maps, 8, 3, 4).x, normal_at(maps, 8, 1, 4).x, 0.01);
  for (int x = 4; x < 8; ++x) EXPECT_GT(normal_at(maps, 8, x, 4).z, 0.9);
  EXPECT_THROW(bake_relief_maps(TexelCanvas(4, 4, false), 1), InternalError);
}

}  // namespace
}  // namespace cutaway
