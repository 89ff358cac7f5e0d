#include "pieces/shaded_mesh.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace cutaway {

unsigned copy_vertex(const ShadedMesh& from, unsigned i, ShadedMesh& to) {
  to.position.push_back(from.position[i]);
  to.normal.push_back(from.normal[i]);
  to.colour.push_back(from.colour[i]);
  to.material.push_back(from.material[i]);
  if (!from.param.empty()) to.param.push_back(from.param[i]);
  return static_cast<unsigned>(to.position.size() - 1);
}

unsigned add_interpolated_vertex(ShadedMesh& mesh, unsigned a, unsigned b, double t) {
  // Copies first: push_back may reallocate under the references.
  const glm::dvec3 pa = mesh.position[a], pb = mesh.position[b];
  const glm::dvec3 na = mesh.normal[a], nb = mesh.normal[b];
  const glm::dvec3 ca = mesh.colour[a], cb = mesh.colour[b];
  const glm::dvec2 ma = mesh.material[a], mb = mesh.material[b];
  mesh.position.push_back(pa + (pb - pa) * t);
  const glm::dvec3 n = na + (nb - na) * t;
  const double len = glm::length(n);
  mesh.normal.push_back(len > 0 ? n / len : na);
  mesh.colour.push_back(ca + (cb - ca) * t);
  mesh.material.push_back(ma + (mb - ma) * t);
  if (!mesh.param.empty()) {
    const glm::dvec2 qa = mesh.param[a];
    glm::dvec2 qb = mesh.param[b];
    if (qb.y - qa.y > 0.5) qb.y -= 1;  // across t_section = 0: the short way
    if (qa.y - qb.y > 0.5) qb.y += 1;
    glm::dvec2 q = qa + (qb - qa) * t;
    q.y -= std::floor(q.y);
    mesh.param.push_back(q);
  }
  return static_cast<unsigned>(mesh.position.size() - 1);
}

void remove_unused_vertices(ShadedMesh& mesh) {
  std::vector<unsigned> remap(mesh.position.size(), ~0u);
  for (const glm::uvec3& t : mesh.triangle)
    for (int k = 0; k < 3; ++k) remap[t[k]] = 0;
  ShadedMesh out;
  for (unsigned i = 0; i < mesh.position.size(); ++i)
    if (remap[i] == 0) remap[i] = copy_vertex(mesh, i, out);
  for (glm::uvec3 t : mesh.triangle)
    out.triangle.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  mesh = std::move(out);
}

void flip(ShadedMesh& mesh) {
  for (glm::uvec3& t : mesh.triangle) std::swap(t[1], t[2]);
  for (glm::dvec3& n : mesh.normal) n = -n;
}

double signed_volume(const ShadedMesh& mesh) {
  double six_v = 0;
  for (const glm::uvec3& t : mesh.triangle) {
    six_v += glm::dot(mesh.position[t[0]], glm::cross(mesh.position[t[1]], mesh.position[t[2]]));
  }
  return six_v / 6;
}

}  // namespace cutaway
