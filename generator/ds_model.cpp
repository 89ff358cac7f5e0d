#include "ds_model.h"

#include <limits>

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

}  // namespace cutaway
