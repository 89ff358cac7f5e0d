#include "export/vertex_tangents.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace cutaway {

namespace {

/// A unit vector orthogonal to unit `n`.
glm::dvec3 any_perpendicular(const glm::dvec3& n) {
  const glm::dvec3 axis = std::fabs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(n, axis));
}

}  // namespace

std::vector<glm::dvec4> vertex_tangents(const std::vector<glm::dvec3>& position,
                                        const std::vector<glm::dvec3>& normal,
                                        const std::vector<glm::dvec2>& uv,
                                        const std::vector<std::span<const glm::uvec3>>& lists) {
  const size_t n = position.size();
  std::vector<glm::dvec3> along_u(n, glm::dvec3(0.0)), along_v(n, glm::dvec3(0.0));
  for (const auto& list : lists)
    for (const glm::uvec3& t : list) {
      const glm::dvec3 e1 = position[t.y] - position[t.x], e2 = position[t.z] - position[t.x];
      const glm::dvec2 d1 = uv[t.y] - uv[t.x], d2 = uv[t.z] - uv[t.x];
      const double det = d1.x * d2.y - d2.x * d1.y;
      if (det == 0 || !std::isfinite(det)) continue;
      // d(position)/du and d(position)/dv of the triangle's affine map from uv to the surface,
      // times |det|: each triangle weighted by its area in uv.
      const double s = det > 0 ? 1.0 : -1.0;
      const glm::dvec3 du = (e1 * d2.y - e2 * d1.y) * s, dv = (e2 * d1.x - e1 * d2.x) * s;
      for (int k = 0; k < 3; ++k) {
        along_u[t[k]] += du;
        along_v[t[k]] += dv;
      }
    }
  std::vector<glm::dvec4> out(n);
  for (size_t i = 0; i < n; ++i) {
    const double length = glm::length(normal[i]);
    const glm::dvec3 nrm = length > 0 ? normal[i] / length : glm::dvec3(0, 1, 0);
    glm::dvec3 t = along_u[i] - nrm * glm::dot(nrm, along_u[i]);
    const double t_length = glm::length(t);
    if (!(t_length > 1e-12 * (glm::length(along_u[i]) + 1e-300))) {
      out[i] = glm::dvec4(any_perpendicular(nrm), 1.0);
      continue;
    }
    t /= t_length;
    const double w = glm::dot(glm::cross(nrm, t), -along_v[i]) < 0 ? -1.0 : 1.0;
    out[i] = glm::dvec4(t, w);
  }
  return out;
}

}  // namespace cutaway
