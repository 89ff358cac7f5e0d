#include "model/model_builder.h"

#include <algorithm>

#include "model/mesh_surface.h"
#include "model/model_checks.h"
#include "model/part_placement.h"
#include "model/spine_bend.h"
#include "model/sweep.h"

namespace cutaway {

DsModel build_model(const Template& t) {
  DsModel model;
  model.name = t.name;
  model.halves_across = t.halves_across;
  std::vector<int> order{t.skin};
  for (int i = 0; i < static_cast<int>(t.surfaces.size()); ++i)
    if (i != t.skin) order.push_back(i);
  size_t vertices = 0;  // so far, over all surfaces: each gets what is left of the budget
  for (int i : order) {
    const SurfaceSpec& spec = t.surfaces[i];
    const size_t left = kMaxModelVertices - std::min(vertices, kMaxModelVertices);
    switch (spec.kind) {
      case SurfaceKind::Around: model.surfaces.push_back(sweep_around(spec, t, left)); break;
      case SurfaceKind::Within: model.surfaces.push_back(sweep_within(spec, t, left)); break;
      case SurfaceKind::Mesh: model.surfaces.push_back(mesh_surface(spec, t, left)); break;
    }
    vertices += model.surfaces.back().mesh.n_vertices();
    set_material(model.surfaces.back().mesh, spec.material_front, spec.material_back);
  }
  update_bounds(model);
  place_parts(t, order, model);
  check_model(t, model, order);
  // The rules above hold in the straight frame; a bend that keeps every stretch positive keeps
  // them (bend_model refuses one that does not).
  bend_model(t, model);
  return model;
}

}  // namespace cutaway
