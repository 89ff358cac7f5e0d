#include "assets/backdrop.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "base/constants.h"

namespace cutaway {

namespace {

constexpr int kCoveSteps = 12;          // segments of the cove's quarter circle
constexpr double kSteepestRise = 80.0;  // degrees: a steeper ray is followed at this rise

}  // namespace

std::optional<AssetMesh> backdrop_sweep(const AssetCamera& camera, const glm::dvec3& lo,
                                        const glm::dvec3& hi, const glm::dvec3& colour) {
  if (!(camera.eye.y > 0)) return std::nullopt;
  const glm::dvec3 up(0, 1, 0);
  const glm::dvec3 centre(0.5 * (lo.x + hi.x), 0, 0.5 * (lo.z + hi.z));
  const double reach = std::max(0.05, 0.5 * std::hypot(hi.x - lo.x, hi.z - lo.z));
  const CameraFrame frame = camera_frame(camera);
  glm::dvec3 away(frame.forward.x, 0, frame.forward.z);
  away = glm::length(away) > 1e-6 ? glm::normalize(away) : glm::dvec3(0, 0, -1);
  const glm::dvec3 side = glm::normalize(glm::cross(away, up));
  const double cove_start = 1.2 * reach, radius = std::max(2.0 * reach, 0.05);
  const double wall = cove_start + radius;  // the wall's distance beyond the centre
  const double max_slope = std::tan(glm::radians(kSteepestRise));

  // Follow the view's corner rays and its centre ray to the floor or the wall.
  const glm::dvec3 eye = camera.eye - centre;
  const double tan_v = std::tan(0.5 * glm::radians(camera.fov_y_deg));
  const double tan_h = camera.aspect * tan_v;
  double front = std::min(glm::dot(eye, away), 0.0), width = reach, height = std::max(hi.y, radius);
  const std::array<glm::dvec2, 5> corners{{{-1, -1}, {1, -1}, {-1, 1}, {1, 1}, {0, 0}}};
  for (const glm::dvec2& k : corners) {
    glm::dvec3 d = frame.forward + k.x * tan_h * frame.right + k.y * tan_v * frame.up;
    const double run = std::hypot(d.x, d.z);
    d.y = std::clamp(d.y, -max_slope * run, max_slope * run);
    if (d.y < 0) {  // down: to the floor, unless the wall comes first
      const glm::dvec3 p = eye + (eye.y / -d.y) * d;
      if (glm::dot(p, away) <= cove_start) {
        front = std::min(front, glm::dot(p, away));
        width = std::max(width, std::fabs(glm::dot(p, side)));
        continue;
      }
    }
    const double toward = glm::dot(d, away);
    if (toward <= 0) continue;  // rising away from the wall: nothing to meet
    const glm::dvec3 q = eye + ((wall - glm::dot(eye, away)) / toward) * d;
    height = std::max(height, q.y);
    width = std::max(width, std::fabs(glm::dot(q, side)));
  }
  front -= reach;
  width += reach;
  height += reach;

  // The profile across the sweep: (distance beyond the centre, height) and its normal.
  std::vector<glm::dvec2> at{{front, 0}}, normal{{0, 1}};
  for (int i = 0; i <= kCoveSteps; ++i) {
    const double a = 0.5 * kPi * i / kCoveSteps;
    at.push_back({cove_start + radius * std::sin(a), radius * (1 - std::cos(a))});
    normal.push_back({-std::sin(a), std::cos(a)});
  }
  at.push_back({wall, height});
  normal.push_back({-1, 0});

  AssetMesh mesh;
  mesh.name = "backdrop";
  for (size_t i = 0; i < at.size(); ++i) {
    for (const double x : {-width, width}) {
      mesh.position.push_back(centre + at[i].x * away + at[i].y * up + x * side);
      mesh.normal.push_back(normal[i].x * away + normal[i].y * up);
      mesh.colour.push_back(colour);
    }
    if (i == 0) continue;
    const auto a = static_cast<unsigned>(2 * (i - 1)), c = a + 2;
    mesh.triangle.push_back({a, a + 1, c});
    mesh.triangle.push_back({a + 1, c + 1, c});
  }
  return mesh;
}

double farthest_vertex(const AssetCamera& camera, const AssetMesh& mesh) {
  double far = 0;
  for (const glm::dvec3& p : mesh.position) far = std::max(far, glm::distance(p, camera.eye));
  return far;
}

}  // namespace cutaway
