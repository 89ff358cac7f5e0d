// Planar curves of templates: centripetal Catmull-Rom fitting, uniform arc-length resampling and
// the geometric predicates the template rules need (doc/algorithms.md §1).
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

namespace cutaway {

/// A planar polyline; closed curves do not repeat their first point at the end.
using Polyline2 = std::vector<glm::dvec2>;

/// `points` without consecutive duplicates (closer than 1e-12), and for a closed curve without
/// a last point equal to the first.
Polyline2 without_duplicates(const Polyline2& points, bool closed);

/// Samples the centripetal Catmull-Rom spline (alpha = 1/2; Barry-Goldman pyramidal form)
/// through `points`, `per_segment` samples per span; the result passes through every point.
/// Open curves use reflected end tangents. Consecutive duplicate points are removed first.
/// Precondition: at least 2 distinct points. Source: Yuksel, Schaefer, Keyser 2011.
Polyline2 catmull_rom(const Polyline2& points, bool closed, int per_segment = 16);

/// The curve a template means: the Catmull-Rom spline when `smooth`, else the polyline itself
/// (densified so that later resampling keeps its corners).
/// Precondition: at least 2 distinct points (3 when closed).
Polyline2 fit_curve(const Polyline2& points, bool closed, bool smooth);

/// Total arc length (closing segment included when `closed`).
double curve_length(const Polyline2& curve, bool closed);

/// `count` points spaced uniformly by arc length, starting at curve[0]. Open: the first and
/// last points are the curve's ends (count >= 2). Closed: the points split the loop into
/// `count` equal arcs (count >= 3).
Polyline2 resample_uniform(const Polyline2& curve, bool closed, int count);

/// Normalised arc-length parameter (0..1) of every point of `curve`.
std::vector<double> arc_length_parameters(const Polyline2& curve, bool closed);

/// Indices (i, j) of two non-adjacent segments that intersect or overlap, or nullopt.
/// Segment i joins point i and i + 1 (mod size when closed).
std::optional<std::pair<size_t, size_t>> find_self_intersection(const Polyline2& curve,
                                                                bool closed);

/// Signed area of a closed polygon (positive when counter-clockwise in its own x-y frame).
double signed_area(const Polyline2& loop);

/// Winding number of a closed polygon around `p`.
int winding_number(const Polyline2& loop, const glm::dvec2& p);

}  // namespace cutaway
