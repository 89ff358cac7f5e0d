#include "model/ds_model.h"

#include <algorithm>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/error.h"

namespace cutaway {

size_t DsModel::face_count() const {
  size_t n = 0;
  for (const auto& s : surfaces) n += s.mesh.n_faces();
  return n;
}

size_t DsModel::vertex_count() const {
  size_t n = 0;
  for (const auto& s : surfaces) n += s.mesh.n_vertices();
  return n;
}

void set_material(DsMesh& mesh, const glm::dvec2& front, const glm::dvec2& back) {
  for (auto vh : mesh.vertices()) {
    auto& d = mesh.data(vh);
    d.material_front = {front.x, front.y};
    d.material_back = {back.x, back.y};
  }
}

void update_bounds(DsModel& model) {
  const double inf = std::numeric_limits<double>::infinity();
  glm::dvec3 lo(inf), hi(-inf);
  for (const auto& s : model.surfaces) {
    for (auto vh : s.mesh.vertices()) {
      const auto& p = s.mesh.point(vh);
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
  }
  model.bbox_min = lo;
  model.bbox_max = hi;
}

std::pair<glm::dvec3, glm::dvec3> mesh_bounds(const DsMesh& mesh) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const auto vh : mesh.vertices()) {
    lo = glm::min(lo, to_glm(mesh.point(vh)));
    hi = glm::max(hi, to_glm(mesh.point(vh)));
  }
  CUTAWAY_CHECK(hi.x >= lo.x);
  return {lo, hi};
}

double signed_volume(const DsMesh& mesh) {
  double six_v = 0;
  for (auto fh : mesh.faces()) {
    std::array<glm::dvec3, 3> p;
    int k = 0;
    for (auto vh : mesh.fv_range(fh)) p[k++] = to_glm(mesh.point(vh));
    six_v += glm::dot(p[0], glm::cross(p[1], p[2]));
  }
  return six_v / 6;
}

std::pair<glm::dvec3, glm::dvec3> skin_bounds(const DsModel& model) {
  return mesh_bounds(model.skin().mesh);
}

Plane mid_height_plane(const DsModel& model) {
  const auto [lo, hi] = skin_bounds(model);
  return {{0, 0.5 * (lo.y + hi.y), 0}, {0, 1, 0}};
}

std::vector<glm::dvec3> vertex_normals(const DsMesh& mesh) {
  std::vector<glm::dvec3> n(mesh.n_vertices(), glm::dvec3(0.0));
  for (auto fh : mesh.faces()) {
    std::array<glm::dvec3, 3> p;
    std::array<int, 3> v;
    int k = 0;
    for (auto vh : mesh.fv_range(fh)) {
      p[k] = to_glm(mesh.point(vh));
      v[k++] = vh.idx();
    }
    const glm::dvec3 fn = glm::cross(p[1] - p[0], p[2] - p[0]);  // length = 2 * area
    for (int c : v) n[c] += fn;
  }
  for (auto& x : n) {
    const double len = glm::length(x);
    x = len > 0 ? x / len : glm::dvec3(0.0);
  }
  return n;
}

bool is_blurred(const DsMesh& mesh) {
  for (auto vh : mesh.vertices())
    if (mesh.data(vh).blur > 0) return true;
  return false;
}

glm::dvec3 blur_sheet_point(const DsMesh& mesh, const std::vector<glm::dvec3>& normals,
                            DsMesh::VertexHandle vh, int side) {
  const glm::dvec3 p = to_glm(mesh.point(vh));
  if (side == 0) return p;
  return p + normals[vh.idx()] * (side * std::max(mesh.data(vh).blur, kMinSheetOffset_m));
}

}  // namespace cutaway
