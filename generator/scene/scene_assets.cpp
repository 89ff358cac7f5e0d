#include "scene/scene_assets.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace cutaway {

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
