#include "scene/scene_assets.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace cutaway {

std::string camera_defect(const AssetCamera& c, bool needs_up) {
  const auto finite = [](const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  if (!finite(c.eye) || !finite(c.target) || !finite(c.up))
    return "eye, target and up must be finite";
  const glm::dvec3 forward = c.target - c.eye;
  if (!(glm::length(forward) > 0)) return "eye and target coincide";
  if (needs_up && (!(glm::length(c.up) > 0) ||
                   !(glm::length(glm::cross(glm::normalize(forward), c.up)) >
                     1e-9 * glm::length(c.up))))
    return "up is zero or parallel to the view direction";
  if (!(c.fov_y_deg > 0 && c.fov_y_deg < 180))
    return "fov_y_deg must be in (0, 180), not " + std::to_string(c.fov_y_deg);
  if (!(c.aspect > 0 && std::isfinite(c.aspect))) return "aspect must be positive and finite";
  if (!(c.znear > 0 && c.znear < c.zfar && std::isfinite(c.zfar)))
    return "need 0 < znear < zfar (finite), not " + std::to_string(c.znear) + ", " +
           std::to_string(c.zfar);
  return "";
}

CameraFrame camera_frame(const AssetCamera& camera) {
  CameraFrame f;
  f.forward = glm::normalize(camera.target - camera.eye);
  f.right = glm::normalize(glm::cross(f.forward, camera.up));
  f.up = glm::cross(f.right, f.forward);
  return f;
}

glm::dmat4 view_from_scene(const AssetCamera& camera) {
  return glm::lookAt(camera.eye, camera.target, camera.up);
}

double focal_length_px(const AssetCamera& camera, int height_px) {
  return height_px / (2 * std::tan(glm::radians(camera.fov_y_deg) / 2));
}

std::span<const glm::uvec3> primitive_triangles(const AssetMesh& mesh, const AssetPrimitive& p,
                                                bool textured) {
  if (textured && !p.coarse.empty()) return p.coarse;
  return std::span<const glm::uvec3>(mesh.triangle).subspan(p.first, p.count);
}

std::string primitives_defect(const AssetMesh& mesh, size_t materials) {
  if (mesh.primitives.empty() && materials == 0) return "material index out of range";
  size_t next = 0;
  for (const AssetPrimitive& p : mesh.primitives) {
    if (p.first != next || p.count == 0) return "primitives must cover the triangles in order";
    if (p.material < 0 || static_cast<size_t>(p.material) >= materials)
      return "material index out of range";
    next += p.count;
  }
  if (!mesh.primitives.empty() && next != mesh.triangle.size())
    return "primitives must cover the triangles in order";
  return "";
}

}  // namespace cutaway
