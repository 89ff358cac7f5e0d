// The geometric rules of the template format that concern the drawn curves
// (doc/template-format.md: self-intersecting curves, a section loop that does not surround the
// axis, a `within` loop that leaves its fold, fewer than 3 points, monotonic rails). Rules that
// need the swept surfaces (a nested surface crossing the skin) are in model_checks.h.
#pragma once

#include "model/template.h"

namespace cutaway {

/// Checks every surface's profile and section curves, as fitted (smooth or polyline), and the
/// spine (rising from bottom to top; not for symmetry none).
/// @throws InputError at the profile or section of the first surface breaking a rule, or at
///         `spine`
void check_template_curves(const Template& tmpl);

/// Angular span [lo, hi] (radians, lo < hi, hi - lo <= 2 pi) of fold k: from half way to the
/// previous fold's centre to half way to the next one's (doc/template-format.md, Frame and
/// units).
std::pair<double, double> fold_span(const Template& tmpl, int k);

/// Angle about +Y of a horizontal point [x, z]: from +X (0) towards -Z (pi/2), radians in
/// (-pi, pi] (doc/template-format.md, Frame and units).
double horizontal_angle(const glm::dvec2& xz);

/// `a` (radians) wrapped into (-pi, pi].
double wrap_angle(double a);

}  // namespace cutaway
