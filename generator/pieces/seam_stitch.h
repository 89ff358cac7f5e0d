// Stitching the parts of a piece along their seams (doc/algorithms.md §4): the clipped skin,
// the clipped walls and the caps are made separately, so a seam can carry a vertex on one side
// that the other side lacks (a T-junction: a Steiner point of the cap's refinement, or a skin
// crossing inside a merged cut segment). Stitching makes both sides share every seam vertex, so
// that the parts together form a closed, crack-free surface.
#pragma once

#include <vector>

#include "pieces/shaded_mesh.h"

namespace cutaway {

/// Counts of what stitch_seams changed.
struct StitchStats {
  size_t snapped = 0;   ///< boundary vertices moved onto another part's boundary vertex
  size_t inserted = 0;  ///< vertices inserted into boundary edges (T-junctions resolved)
};

/// Makes the boundaries of `parts` meet vertex to vertex:
/// 1. every boundary vertex (on an edge used by one triangle of its part) within `tolerance_m`
///    of a boundary vertex of an earlier part (in part order, then vertex order) takes that
///    vertex's position exactly;
/// 2. every boundary edge gets the boundary vertices of other parts that lie on it (within
///    `tolerance_m` of the segment, strictly between its ends): its triangle is split into a
///    fan from the opposite corner (or, when more than one of its edges gets vertices, from a
///    new vertex at its centroid); new vertices interpolate normal and colour along the edge.
/// Deterministic. Vertices inside a part are never merged with each other.
/// @param tolerance_m  > 0; smaller than half the shortest boundary edge of any part
StitchStats stitch_seams(std::vector<ShadedMesh*>& parts, double tolerance_m);

}  // namespace cutaway
