#include "model/model_builder.h"

#include "model/mesh_import.h"
#include "model/model_checks.h"
#include "model/sweep.h"

namespace cutaway {

DsModel build_model(const Template& t) {
  DsModel model;
  model.name = t.name;
  std::vector<int> order{t.skin};
  for (int i = 0; i < static_cast<int>(t.surfaces.size()); ++i)
    if (i != t.skin) order.push_back(i);
  for (int i : order) {
    const SurfaceSpec& spec = t.surfaces[i];
    switch (spec.kind) {
      case SurfaceKind::Around: model.surfaces.push_back(sweep_around(spec, t)); break;
      case SurfaceKind::Within: model.surfaces.push_back(sweep_within(spec, t)); break;
      case SurfaceKind::Mesh: model.surfaces.push_back(import_mesh_surface(spec, t)); break;
    }
    set_material(model.surfaces.back().mesh, spec.material_front, spec.material_back);
  }
  update_bounds(model);
  check_model(t, model, order);
  return model;
}

}  // namespace cutaway
