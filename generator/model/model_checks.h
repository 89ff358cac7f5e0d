// Geometric rules that need the swept surfaces (doc/template-format.md, Errors: every surface
// other than the skin lies inside it without touching or crossing it).
#pragma once

#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// Checks that the skin (model.surfaces[0]) is closed and that every other surface lies inside
/// it without touching or crossing it. Exact predicates (CGAL Epick): triangle-triangle
/// intersection (PMP::do_intersect) and point-in-closed-mesh (Side_of_triangle_mesh).
/// @param surface_specs  model.surfaces[i] was made from tmpl.surfaces[surface_specs[i]]
/// @throws InputError at the offending surface of the template
void check_model(const Template& tmpl, const DsModel& model, const std::vector<int>& surface_specs);

}  // namespace cutaway
