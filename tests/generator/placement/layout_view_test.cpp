// What of the camera a layout is made for (layout_view) and the seeded order pieces are laid
// out in (placement_order), doc/algorithms.md §4: a round container turns the camera to the
// front and back again, a board to its nearest side, and a camera straight above or below
// counts as at the front.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/constants.h"
#include "placement/scene_layout.h"

namespace cutaway {
namespace {

/// The unit direction towards a camera at `azimuth` (0 at the front, +Z, counter-clockwise
/// seen from above) and `elevation` above the horizon, radians.
glm::dvec3 towards(double azimuth, double elevation) {
  return {std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
          std::cos(azimuth) * std::cos(elevation)};
}

double degrees(double radians) { return radians * 180 / kPi; }

TEST(LayoutView, ARoundContainerIsLaidOutForTheFrontAndTurnedBackByTheAzimuth) {
  Container bowl;
  bowl.type = ContainerType::Bowl;
  for (const double azimuth_deg : {-170.0, -40.0, 0.0, 40.0, 100.0}) {
    const double azimuth = azimuth_deg * kPi / 180;
    const LayoutView view = layout_view(bowl, towards(azimuth, 0.6));
    const glm::dvec3 front = towards(0, 0.6);
    EXPECT_LT(glm::length(view.to_camera - front), 1e-8) << azimuth_deg;
    EXPECT_NEAR(degrees(view.turn_back), azimuth_deg, 1e-9);
  }
}

TEST(LayoutView, ABoardIsLaidOutForItsNearestSideAndNotTurned) {
  Container board;
  board.type = ContainerType::Board;
  const struct {
    double azimuth_deg, side_deg;
  } cases[] = {{0, 0}, {40, 0}, {-44, 0}, {46, 90}, {100, 90}, {-100, -90}, {170, 180}};
  for (const auto& c : cases) {
    const LayoutView view = layout_view(board, towards(c.azimuth_deg * kPi / 180, 0.6));
    EXPECT_LT(glm::length(view.to_camera - towards(c.side_deg * kPi / 180, 0.6)), 1e-8)
        << c.azimuth_deg;
    EXPECT_EQ(view.turn_back, 0.0);
  }
}

TEST(LayoutView, TheElevationIsRoundedSoThatAnOrbitGivesTheSameDirectionBitForBit) {
  Container plate;
  plate.type = ContainerType::Plate;
  const glm::dvec3 front = layout_view(plate, towards(0, 0.7)).to_camera;
  for (const double azimuth : {0.3, 1.1, 2.9, -2.0}) {
    // The same elevation reached through another azimuth differs in its last bits.
    const glm::dvec3 orbited = glm::normalize(towards(azimuth, 0.7) * 3.0);
    const glm::dvec3 seen = layout_view(plate, orbited).to_camera;
    EXPECT_EQ(seen.x, front.x);
    EXPECT_EQ(seen.y, front.y);
    EXPECT_EQ(seen.z, front.z);
  }
}

TEST(LayoutView, ACameraStraightAboveOrBelowCountsAsAtTheFront) {
  for (const ContainerType type : {ContainerType::Bowl, ContainerType::Board}) {
    Container container;
    container.type = type;
    for (const double y : {1.0, -1.0}) {
      const LayoutView view = layout_view(container, {0, y, 0});
      EXPECT_EQ(view.turn_back, 0.0);
      EXPECT_NEAR(view.to_camera.y, y, 1e-12);
      EXPECT_NEAR(glm::length(view.to_camera), 1.0, 1e-12);
      EXPECT_TRUE(std::isfinite(view.to_camera.x) && std::isfinite(view.to_camera.z));
    }
  }
}

TEST(PlacementOrder, IsASeededPermutation) {
  const std::vector<size_t> a = placement_order(263, 7);
  std::vector<size_t> sorted = a;
  std::sort(sorted.begin(), sorted.end());
  std::vector<size_t> identity(263);
  std::iota(identity.begin(), identity.end(), size_t{0});
  EXPECT_EQ(sorted, identity);
  EXPECT_NE(a, identity);
  EXPECT_EQ(placement_order(263, 7), a);
  EXPECT_NE(placement_order(263, 8), a);
  EXPECT_TRUE(placement_order(0, 7).empty());
}

}  // namespace
}  // namespace cutaway
