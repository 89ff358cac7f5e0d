#include "section/grain_neighbourhood.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace cutaway {

GrainNeighbourhood::GrainNeighbourhood(const DsModel& model, const Plane& plane) {
  for (const DsSurface& surface : model.surfaces) {
    if (surface.role != SurfaceRole::Grain) continue;
    const DsMesh& mesh = surface.mesh;
    // Connected components by a flood over the vertices' neighbours, in vertex order.
    std::vector<bool> seen(mesh.n_vertices(), false);
    std::vector<glm::dvec3> members;
    for (auto start : mesh.vertices()) {
      if (seen[start.idx()]) continue;
      seen[start.idx()] = true;
      std::vector<OpenMesh::VertexHandle> stack{start};
      members.clear();
      while (!stack.empty()) {
        const auto v = stack.back();
        stack.pop_back();
        const auto& p = mesh.point(v);
        members.emplace_back(p[0], p[1], p[2]);
        for (auto w : mesh.vv_range(v))
          if (!seen[w.idx()]) {
            seen[w.idx()] = true;
            stack.push_back(w);
          }
      }
      glm::dvec3 lo = members.front(), hi = members.front();
      for (const glm::dvec3& q : members) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
      }
      const glm::dvec3 centre = 0.5 * (lo + hi);
      double radius = 0;
      for (const glm::dvec3& q : members) radius = std::max(radius, glm::distance(q, centre));
      const double reach = kNearGrainRadii * radius;
      if (std::fabs(glm::dot(centre - plane.point, plane.normal)) >= reach) continue;
      centre_.push_back(centre);
      reach_.push_back(reach);
    }
  }
}

bool GrainNeighbourhood::near(const glm::dvec3& p) const {
  for (size_t g = 0; g < centre_.size(); ++g)
    if (glm::distance(p, centre_[g]) < reach_[g]) return true;
  return false;
}

}  // namespace cutaway
