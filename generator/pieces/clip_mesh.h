// Clipping a triangle mesh to a half-space (doc/algorithms.md §4: the skin and the walls of
// hollow regions clipped to a piece's convex cell), with the same on-plane rule as the cut
// segments, so clipped boundaries meet the caps' cut loops.
#pragma once

#include "pieces/shaded_mesh.h"
#include "section/cut_segments.h"

namespace cutaway {

/// Keeps the part of `mesh` where dot(x - p, n) <= 0 (`keep_positive` false) or >= 0 (true).
/// A vertex within kOnPlane_m of the plane lies on it and counts as positive (the rule of
/// cut_segments()): it is kept by a positive cell, and for a negative cell the boundary passes
/// through it. A crossing is computed once per mesh edge from its positive end, and shared by
/// both triangles at that edge, so a closed mesh gets a closed boundary; new vertices
/// interpolate normal and colour linearly. Triangles cut in two become one or two triangles.
/// Unused vertices are dropped.
/// @param plane  unit normal
ShadedMesh clip_to_half_space(const ShadedMesh& mesh, const Plane& plane, bool keep_positive);

}  // namespace cutaway
