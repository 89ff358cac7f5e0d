// The backdrop sweep (assets/backdrop.h): whatever the camera above the table, every ray of its
// view meets the sweep from the front, the floor is the plane y = 0 under the content and the
// wall stands beyond it, away from the camera; a camera below the table gets none.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "assets/asset_camera.h"
#include "assets/backdrop.h"

namespace cutaway {
namespace {

struct Hit {
  double t;           // distance along the unit ray
  glm::dvec3 normal;  // the triangle's geometric normal (its winding)
};

/// The nearest triangle of `mesh` that the ray from `origin` along the unit `d` meets
/// (Moller-Trumbore), if any.
std::optional<Hit> first_hit(const AssetMesh& mesh, const glm::dvec3& origin, const glm::dvec3& d) {
  std::optional<Hit> best;
  for (const glm::uvec3& t : mesh.triangle) {
    const glm::dvec3 a = mesh.position[t.x], b = mesh.position[t.y], c = mesh.position[t.z];
    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (std::fabs(det) < 1e-18) continue;
    const glm::dvec3 s = origin - a;
    const double u = glm::dot(s, p) / det;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) / det, dist = glm::dot(e2, q) / det;
    if (u < -1e-9 || v < -1e-9 || u + v > 1 + 1e-9 || dist <= 0) continue;
    if (!best || dist < best->t) best = Hit{dist, glm::normalize(glm::cross(e1, e2))};
  }
  return best;
}

/// Every ray of a 9 x 9 grid over `camera`'s image (corners included) meets the sweep, on its
/// front, within the far clipping distance that keeps the whole sweep in view.
void expect_view_covered(const AssetCamera& camera, const AssetMesh& sweep) {
  const CameraFrame f = camera_frame(camera);
  const double tan_v = std::tan(0.5 * glm::radians(camera.fov_y_deg));
  const double tan_h = camera.aspect * tan_v, far = farthest_vertex(camera, sweep);
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j) {
      const double x = -1 + i / 4.0, y = -1 + j / 4.0;
      const glm::dvec3 d = glm::normalize(f.forward + x * tan_h * f.right + y * tan_v * f.up);
      const std::optional<Hit> hit = first_hit(sweep, camera.eye, d);
      ASSERT_TRUE(hit) << "the ray through (" << x << ", " << y << ") misses the sweep";
      EXPECT_LT(glm::dot(hit->normal, d), 0)
          << "it meets the sweep's back at (" << x << ", " << y << ")";
      EXPECT_LE(hit->t, far);
    }
}

const glm::dvec3 kLo(-0.15, 0, -0.12), kHi(0.15, 0.1, 0.12);  // a salad on a board
const glm::dvec3 kLinen(0.43, 0.39, 0.34);

TEST(Backdrop, TheDefaultViewSeesOnlyTheSweep) {
  const AssetCamera camera = frame_box(kLo, kHi, {0, std::sin(0.87), std::cos(0.87)}, 40, 4.0 / 3);
  const std::optional<AssetMesh> made = backdrop_sweep(camera, kLo, kHi, kLinen);
  ASSERT_TRUE(made);
  const AssetMesh& sweep = *made;
  EXPECT_EQ(sweep.name, "backdrop");
  expect_view_covered(camera, sweep);
  for (const glm::dvec3& c : sweep.colour) EXPECT_EQ(c, kLinen);
  // The floor lies at y = 0 under the content, facing up; the wall stands beyond it (-Z, away
  // from a camera on +Z), facing the camera.
  const std::optional<Hit> floor = first_hit(sweep, {0, 1, 0}, {0, -1, 0});
  ASSERT_TRUE(floor);
  EXPECT_NEAR(floor->t, 1.0, 1e-12);
  EXPECT_GT(floor->normal.y, 0.999);
  const std::optional<Hit> wall = first_hit(sweep, {0, 0.45, 0}, {0, 0, -1});
  ASSERT_TRUE(wall);
  EXPECT_GT(wall->t, glm::length(kHi - kLo) / 2);
  EXPECT_GT(wall->normal.z, 0.999);
  EXPECT_FALSE(first_hit(sweep, {0, 0.45, 0}, {0, 0, 1})) << "no wall on the camera's side";
}

TEST(Backdrop, LowWideAndTopDownViewsAreCoveredToo) {
  // Nearly level and looking up a little: the wall must rise above the top of the view.
  AssetCamera low;
  low.eye = {0.1, 0.03, 0.6};
  low.target = {0, 0.08, 0};
  low.fov_y_deg = 60;
  low.aspect = 16.0 / 9;
  expect_view_covered(low, backdrop_sweep(low, kLo, kHi, kLinen).value());
  // Wide (127 degrees across): the sweep runs far to the sides.
  AssetCamera wide = frame_box(kLo, kHi, {1, 0.3, 0.2}, 90, 2.0);
  expect_view_covered(wide, backdrop_sweep(wide, kLo, kHi, kLinen).value());
  // Straight down: all floor; the wall is taken to stand toward -Z.
  AssetCamera top;
  top.eye = {0, 1, 0};
  top.target = {0, 0, 0};
  top.up = stable_camera_up(top.target - top.eye);
  expect_view_covered(top, backdrop_sweep(top, kLo, kHi, kLinen).value());
  // A point of content: the sweep keeps a size of its own.
  const AssetCamera point = frame_box(glm::dvec3(0), glm::dvec3(0), {0, 1, 1}, 40, 4.0 / 3);
  expect_view_covered(point, backdrop_sweep(point, glm::dvec3(0), glm::dvec3(0), kLinen).value());
}

TEST(Backdrop, ACameraBelowTheTableGetsNone) {
  // From under the floor the table's underside would hide everything above it.
  AssetCamera below;
  below.eye = {0, -0.05, 0.4};
  below.target = {0, 0.03, 0};
  EXPECT_FALSE(backdrop_sweep(below, kLo, kHi, kLinen));
  below.eye.y = 0;
  EXPECT_FALSE(backdrop_sweep(below, kLo, kHi, kLinen));
  below.eye.y = 0.001;
  EXPECT_TRUE(backdrop_sweep(below, kLo, kHi, kLinen));
}

}  // namespace
}  // namespace cutaway
