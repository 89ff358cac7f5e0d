#include "model/part_placement.h"

#include <cmath>

#include <glm/mat3x3.hpp>

#include "model/inside_test.h"

namespace cutaway {

void place_parts(const Template& t, const std::vector<int>& specs, DsModel& model) {
  bool moved = false;
  // In template order: specs[i] is the template index of model surface i.
  for (int spec_index = 0; spec_index < static_cast<int>(t.surfaces.size()); ++spec_index) {
    const SurfaceSpec& spec = t.surfaces[static_cast<size_t>(spec_index)];
    if (spec.offset_m == glm::dvec3(0.0) && spec.tilt_rad == glm::dvec2(0.0)) continue;
    size_t s = 0;
    while (s < specs.size() && specs[s] != spec_index) ++s;
    if (s == specs.size()) continue;
    const auto [lo, hi] = mesh_bounds(model.surfaces[s].mesh);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double cx = std::cos(spec.tilt_rad.x), sx = std::sin(spec.tilt_rad.x);
    const double cz = std::cos(spec.tilt_rad.y), sz = std::sin(spec.tilt_rad.y);
    // Column-major: Rx about +X, Rz about +Z.
    const glm::dmat3 rx(1, 0, 0, 0, cx, sx, 0, -sx, cx);
    const glm::dmat3 rz(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
    const glm::dmat3 turn = rz * rx;
    std::vector<size_t> group = surfaces_inside(model, s);
    group.push_back(s);
    for (size_t g : group) {
      DsMesh& mesh = model.surfaces[g].mesh;
      for (auto vh : mesh.vertices()) {
        const glm::dvec3 p = turn * (to_glm(mesh.point(vh)) - centre) + centre + spec.offset_m;
        mesh.set_point(vh, DsMesh::Point(p.x, p.y, p.z));
      }
    }
    moved = true;
  }
  if (moved) update_bounds(model);
}

}  // namespace cutaway
