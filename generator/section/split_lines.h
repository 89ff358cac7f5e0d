// Split lines of a restricted cross-section (doc/algorithms.md §4, Restricted cross-sections:
// the lines of the other planes are extra constraints): where the other cutting planes of a
// cut meet this plane, and the planar arrangement of those lines with the cut segments, so
// that no two constraints cross (CGAL's Delaunay refinement is not reliable with crossing
// constraints whose crossings are computed inexactly).
#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "section/cut_segments.h"

namespace cutaway {

/// A line a x + b y = c of plane coordinates, (a, b) unit.
struct Line2 {
  glm::dvec2 normal{1, 0};
  double offset = 0;
};

/// The distinct lines where `others` meet the plane with origin `plane.point` and in-plane axes
/// u, v (metres). Planes parallel to it give none; several planes through one line (wedges)
/// give it once.
std::vector<Line2> split_lines(const Plane& plane, const glm::dvec3& u, const glm::dvec3& v,
                               const std::vector<Plane>& others);

/// One constraint of the arrangement: a piece of cut segment `segment`, or of a split line
/// (segment -1).
struct Constraint2 {
  glm::dvec2 a{0.0}, b{0.0};
  int segment = -1;
};

/// Cuts the segments (#S, each a pair of end points) and the lines (clipped to the box lo..hi)
/// at their crossings so that constraints only meet at shared end points. A segment end point
/// within `snap_m` of a line lies on it (the line bends by at most snap_m there to pass
/// through it), so no crossing is made a hair's breadth from a cut vertex. Crossings of two lines
/// inside the box split both. Zero-length pieces are dropped. Deterministic: segments in input
/// order, then lines.
std::vector<Constraint2> arrange_split_lines(
    const std::vector<std::pair<glm::dvec2, glm::dvec2>>& segments, const std::vector<Line2>& lines,
    const glm::dvec2& lo, const glm::dvec2& hi, double snap_m);

}  // namespace cutaway
