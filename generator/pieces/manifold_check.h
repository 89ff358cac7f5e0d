// Whether a piece's surface is a closed, consistently oriented 2-manifold without slivers: the
// property every piece of an object whose skin is closed must have (pieces.h), checked on each
// cut so that a near-degenerate configuration is redone rather than exported.
#pragma once

#include "base/outcome.h"
#include "pieces/shaded_mesh.h"

namespace cutaway {

/// Passes when `mesh` (vertices welded by exact position) has no defect, else fails with the
/// first one in words. Defects, in the order checked:
/// - a triangle with two corners at one point, or of zero area;
/// - a directed edge used more than once, or without a twin running the other way (an open or
///   inconsistently oriented surface);
/// - a vertex whose triangles form more than one fan (two sheets touching at a point);
/// - two distinct vertices closer than `min_separation_m` (metres; near-duplicates that only
///   close after a weld). 0 skips this check.
/// Deterministic; O(#F log #F).
Check check_manifold(const ShadedMesh& mesh, double min_separation_m);

}  // namespace cutaway
