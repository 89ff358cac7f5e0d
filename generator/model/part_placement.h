// Inner parts off the axis (doc/template-format.md, Parts off the axis): a surface with an
// `offset` or a `tilt` is moved, with every surface it encloses, after the sweeps, so a yolk, a
// stone or a core need not sit on the axis. A rigid motion keeps every surface's shape; what it
// may break (a part moved into another surface) is refused by check_model afterwards.
#pragma once

#include <vector>

#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// Moves each surface of `model` whose spec has an offset or a tilt (SurfaceSpec::offset_m,
/// tilt_rad) and the surfaces it encloses (inside_test.h; a surface that is not closed moves
/// alone): p -> Rz(tilt.y) Rx(tilt.x) (p - c) + c + offset, c the centre of the surface's
/// bounding box before the move. Surfaces are moved in template order; one enclosed by a
/// moved surface moves with it and then by its own placement. Updates the model's bounds.
/// @param surface_specs  model.surfaces[i] was made from tmpl.surfaces[surface_specs[i]]
void place_parts(const Template& tmpl, const std::vector<int>& surface_specs, DsModel& model);

}  // namespace cutaway
