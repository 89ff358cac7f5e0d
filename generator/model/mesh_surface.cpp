#include "model/mesh_surface.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/common.hpp>

#include "base/error.h"

namespace cutaway {

MeshBounds mesh_bounds(const MeshData& mesh, double metres_per_unit) {
  MeshBounds b;
  bool first = true;
  for (const glm::dvec3& p : mesh.points) {
    const glm::dvec3 q = p * metres_per_unit;
    b.min = first ? q : glm::min(b.min, q);
    b.max = first ? q : glm::max(b.max, q);
    first = false;
  }
  return b;
}

DsSurface mesh_surface(const SurfaceSpec& spec, const Template& tmpl, size_t max_vertices) {
  const std::string field = spec.path + ".file";
  if (!spec.mesh) throw InternalError("mesh_surface: the mesh of " + spec.path + " was not read");
  const MeshData& mesh = *spec.mesh;
  if (mesh.points.size() > max_vertices) {
    throw InputError(spec.mesh_loc, field,
                     "the mesh has " + std::to_string(mesh.points.size()) +
                         " vertices, and the model may have at most " +
                         std::to_string(kMaxModelVertices) + " over all surfaces (" +
                         std::to_string(kMaxModelVertices - max_vertices) +
                         " taken by the surfaces before it)");
  }
  DsSurface s;
  s.name = spec.name;
  s.role = spec.is_skin ? SurfaceRole::Skin : SurfaceRole::Structure;
  s.visible_front = spec.visible_front;
  s.visible_back = spec.visible_back;
  s.rigid = spec.rigid;
  // A closed mesh's front is its outside (doc/template-format.md, Surfaces: Front and back):
  // wound inwards, it is turned.
  const bool turn = mesh.closed && mesh.signed_volume6 < 0;

  // Vertices no triangle uses have no normal and no meaning in a DS: they are left out.
  std::vector<bool> used(mesh.points.size(), false);
  for (const auto& t : mesh.triangles)
    for (int v : t) used[static_cast<size_t>(v)] = true;
  std::vector<DsMesh::VertexHandle> vh(mesh.points.size());
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    if (!used[i]) continue;
    const glm::dvec3 p = mesh.points[i] * tmpl.metres_per_unit;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw InputError(spec.mesh_loc, field, "the mesh has a vertex that is not a finite number");
    }
    auto h = s.mesh.add_vertex(DsMesh::Point(p.x, p.y, p.z));
    auto& d = s.mesh.data(h);
    const glm::dvec3 f = mesh.front.empty() ? spec.front.at(0, 0, tmpl.ripeness) : mesh.front[i];
    const glm::dvec3 b = mesh.back.empty() ? spec.back.at(0, 0, tmpl.ripeness) : mesh.back[i];
    d.front = {f.x, f.y, f.z};
    d.back = {b.x, b.y, b.z};
    d.blur = mesh.blur.empty() ? spec.blur.at(0, 0, tmpl.ripeness)
                               : std::max(0.0, mesh.blur[i] * tmpl.metres_per_unit);
    vh[i] = h;
  }
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    std::vector<DsMesh::VertexHandle> corners;
    for (int v : mesh.triangles[f]) corners.push_back(vh[static_cast<size_t>(v)]);
    if (turn) std::reverse(corners.begin(), corners.end());
    if (!s.mesh.add_face(corners).is_valid()) {
      throw InputError(spec.mesh_loc, field,
                       "the mesh is not an oriented 2-manifold (face " + std::to_string(f) +
                           " makes a complex edge or flips orientation)");
    }
  }
  if (spec.is_skin) {
    for (auto h : s.mesh.halfedges()) {
      if (s.mesh.is_boundary(h)) {
        throw InputError(spec.mesh_loc, field, "the skin must be a closed mesh (it has a hole)");
      }
    }
  }
  return s;
}

}  // namespace cutaway
