#include "diffusion/diffusion_sheets.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace cutaway {

namespace {

glm::vec3 to_vec3(const OpenMesh::Vec3d& v) { return {v[0], v[1], v[2]}; }
glm::vec2 to_vec2(const OpenMesh::Vec2d& v) { return {v[0], v[1]}; }

/// Copies the mesh into a sheet, each vertex at its blur_sheet_point on side `sign` (0: the
/// surface itself, two-faced).
DiffusionSheet sheet_of(const DsMesh& mesh, const std::vector<glm::dvec3>& normals, int sign) {
  DiffusionSheet s;
  for (auto vh : mesh.vertices()) {
    const auto& d = mesh.data(vh);
    s.position.push_back(glm::vec3(blur_sheet_point(mesh, normals, vh, sign)));
    s.colour_front.push_back(to_vec3(sign < 0 ? d.back : d.front));
    s.colour_back.push_back(to_vec3(sign == 0 ? d.back : (sign < 0 ? d.back : d.front)));
    s.material_front.push_back(to_vec2(sign < 0 ? d.material_back : d.material_front));
    s.material_back.push_back(
        to_vec2(sign == 0 ? d.material_back : (sign < 0 ? d.material_back : d.material_front)));
  }
  for (auto fh : mesh.faces()) {
    glm::uvec3 t;
    int k = 0;
    for (auto vh : mesh.fv_range(fh)) t[k++] = static_cast<unsigned>(vh.idx());
    s.triangle.push_back(t);
    const glm::vec3 n =
        glm::cross(s.position[t[1]] - s.position[t[0]], s.position[t[2]] - s.position[t[0]]);
    const float len = glm::length(n);
    s.face_normal.push_back(len > 0 ? n / len : glm::vec3(0));
  }
  s.two_faced = sign == 0;
  return s;
}

}  // namespace

std::vector<DiffusionSheet> make_diffusion_sheets(const DsModel& model) {
  std::vector<DiffusionSheet> sheets;
  for (const DsSurface& surface : model.surfaces) {
    const std::vector<glm::dvec3> normals = vertex_normals(surface.mesh);
    if (is_blurred(surface.mesh)) {
      sheets.push_back(sheet_of(surface.mesh, normals, +1));
      sheets.push_back(sheet_of(surface.mesh, normals, -1));
    } else {
      sheets.push_back(sheet_of(surface.mesh, normals, 0));
    }
  }
  return sheets;
}

std::vector<DiffusionSheet> surface_sheets(const DsModel& model) {
  std::vector<DiffusionSheet> sheets;
  for (const DsSurface& surface : model.surfaces)
    sheets.push_back(sheet_of(surface.mesh, vertex_normals(surface.mesh), 0));
  return sheets;
}

}  // namespace cutaway
