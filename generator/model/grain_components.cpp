#include "model/grain_components.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace cutaway {

std::vector<GrainComponent> grain_components(const DsModel& model) {
  std::vector<GrainComponent> out;
  for (size_t s = 0; s < model.surfaces.size(); ++s) {
    if (model.surfaces[s].role != SurfaceRole::Grain) continue;
    const DsMesh& mesh = model.surfaces[s].mesh;
    std::vector<bool> seen(mesh.n_vertices(), false);
    for (auto start : mesh.vertices()) {
      if (seen[start.idx()]) continue;
      seen[start.idx()] = true;
      GrainComponent grain;
      grain.surface = s;
      std::vector<OpenMesh::VertexHandle> stack{start};
      while (!stack.empty()) {
        const auto v = stack.back();
        stack.pop_back();
        grain.points.push_back(to_glm(mesh.point(v)));
        for (auto w : mesh.vv_range(v))
          if (!seen[w.idx()]) {
            seen[w.idx()] = true;
            stack.push_back(w);
          }
      }
      glm::dvec3 lo = grain.points.front(), hi = lo;
      for (const glm::dvec3& q : grain.points) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
      }
      grain.centre = 0.5 * (lo + hi);
      grain.farthest = grain.points.front();
      for (const glm::dvec3& q : grain.points)
        if (const double d = glm::distance(q, grain.centre); d > grain.radius) {
          grain.radius = d;
          grain.farthest = q;
        }
      out.push_back(std::move(grain));
    }
  }
  return out;
}

}  // namespace cutaway
