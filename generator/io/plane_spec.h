// The command line's cutting-plane notation (doc/architecture.md, Command line).
#pragma once

#include <string>

#include "base/outcome.h"
#include "base/plane.h"

namespace cutaway {

/// Parses `AXIS=VALUE` (x, y or z; e.g. "y=20": the plane y = 20 with normal +Y) or
/// `px,py,pz/nx,ny,nz` (a point and a normal, any length but not zero). Coordinates are in
/// template units and become metres with `metres_per_unit`; the normal is normalised.
/// @returns the plane, or none with the rule `spec` breaks (not of either form, a number out of
///          range, a zero normal)
Outcome<Plane> parse_plane_spec(const std::string& spec, double metres_per_unit);

}  // namespace cutaway
