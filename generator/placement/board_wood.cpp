#include "placement/board_wood.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "base/colour.h"
#include "base/error.h"
#include "base/random.h"
#include "material/perlin_noise.h"

namespace cutaway {
namespace {

constexpr uint64_t kPurposeWood = 0x776f6f64;  // "wood"
constexpr double kRingSpacing_mm = 3.0;        // growth rings, cut lengthwise
constexpr double kBendScale_mm = 90.0;         // how far the rings' bends reach
constexpr double kBendAmount = 5.0;            // rings the bends shift them by, at most about

}  // namespace

AssetTexture board_wood_texture(const Container& board, uint64_t seed) {
  CUTAWAY_CHECK(board.type == ContainerType::Board && board.width_m > 0 && board.depth_m > 0);
  const double width_mm = board.width_m * 1e3, depth_mm = board.depth_m * 1e3;
  const double scale =
      std::min(kBoardWoodTexelsPerMm, kBoardWoodMaxSide / std::max(width_mm, depth_mm));
  AssetTexture t;
  t.name = "board_wood";
  t.channels = 3;
  t.width = std::max(2, static_cast<int>(std::lround(width_mm * scale)));
  t.height = std::max(2, static_cast<int>(std::lround(depth_mm * scale)));
  t.pixels.resize(static_cast<size_t>(t.width) * t.height * 3);
  const PerlinNoise bend(derive_seed(seed, {kPurposeWood, 1}));
  const PerlinNoise streaks(derive_seed(seed, {kPurposeWood, 2}));
  for (int row = 0; row < t.height; ++row) {
    for (int col = 0; col < t.width; ++col) {
      const double x = (col + 0.5) / t.width * width_mm, z = (row + 0.5) / t.height * depth_mm;
      // The ring a point lies in: its distance across the grain, bent along it.
      const double rings = z / kRingSpacing_mm +
                           kBendAmount * bend({x / kBendScale_mm, z / (0.4 * kBendScale_mm), 0.5}) +
                           0.3 * bend({x / 9.0, z / 3.0, 7.5});
      const double phase = rings - std::floor(rings);
      // Latewood: a narrow dark line at the end of each ring, softened on both sides.
      const double late = std::exp(-std::pow((phase - 0.85) / 0.07, 2.0));
      // Pores: fine streaks along the grain (long in x, short in z).
      const double pores = streaks({x / 14.0, z / 0.35, 3.5});
      // Broad tone: some stretches of the board darker, as heartwood and sapwood.
      const double tone = 0.06 * streaks({x / 120.0, z / 60.0, 11.5});
      const double shade = std::clamp(0.93 - 0.27 * late + 0.07 * pores + tone, 0.62, 1.0);
      const glm::dvec3 c = board.colour * shade;
      uint8_t* out = &t.pixels[(static_cast<size_t>(row) * t.width + col) * 3];
      for (int k = 0; k < 3; ++k) out[k] = linear_to_srgb8(c[k]);
    }
  }
  return t;
}

}  // namespace cutaway
