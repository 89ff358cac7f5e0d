// Cut segments (paper §3.2, Fig. 3a; doc/algorithms.md §3 step 1): the intersection of a
// cutting plane with every DS triangle, each piece carrying its surface and the DS attributes
// interpolated at its end points.
#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/plane.h"
#include "model/ds_model.h"

namespace cutaway {

/// Vertices closer to a cutting plane than this (metres) lie on it (symbolic perturbation,
/// shared by cut_segments and clip_to_half_space): sweeps put vertices on planes through the
/// axis up to rounding, and a crossing a few nanometres from a vertex would only add a sliver
/// (two crossings nanometres apart) to the cap and the clipped skin. The vertex keeps its
/// position: the cap's triangulation uses it as it is (make_cross_section).
constexpr double kOnPlane_m = 1e-8;

/// The DS attributes at one point of a surface (ds_model.h, DsMeshTraits).
struct DsAttributes {
  glm::dvec3 front{0.0}, back{0.0};                    ///< linear RGB
  glm::dvec2 material_front{0.0}, material_back{0.0};  ///< (roughness, translucency), 0..1
  double blur = 0;                                     ///< metres

  /// The colour (or material channels) that the `front` or back side shows.
  const glm::dvec3& colour(bool front_side) const { return front_side ? front : back; }
  const glm::dvec2& material(bool front_side) const {
    return front_side ? material_front : material_back;
  }
};

/// (1 - t) * a + t * b, attribute by attribute.
DsAttributes lerp(const DsAttributes& a, const DsAttributes& b, double t);

/// One piece of the intersection of the plane with one DS triangle.
struct CutSegment {
  int surface = -1;              ///< index into DsModel::surfaces
  glm::dvec3 a{0.0}, b{0.0};     ///< end points on the plane, metres
  glm::dvec3 front_normal{0.0};  ///< the triangle's unit normal (points to the front side)
  DsAttributes at_a, at_b;       ///< interpolated at a and at b
};

/// Intersects every triangle of every surface with `plane`. Robust to vertices and edges on
/// the plane by symbolic perturbation: a vertex within kOnPlane_m of the plane lies on it, and a
/// vertex on the plane counts as lying on the positive side, so every crossing is computed once per
/// mesh edge (or vertex) and shared by the triangles around it: the segments of a closed surface
/// form closed loops. Segments of zero length are dropped.
/// @param plane  plane.normal must be unit length
/// @return segments in surface order, then face order (deterministic)
std::vector<CutSegment> cut_segments(const DsModel& model, const Plane& plane);

/// Merges pairs of cut segments of one surface that meet at an end point used by no other
/// segment, where that point lies within `tolerance_m` of the chord of the merged segment and
/// the chord is at most `max_length_m` long (a horizontal plane crosses both triangles of each
/// quad of a sweep: two nearly collinear segments per quad). The merged segment keeps the
/// outer end points' attributes and the first segment's normal. Two segments are not merged
/// where their three end points are not all strictly on one side of every plane of
/// `split_planes` (the other planes of a cut): there the merged chord would cross that plane
/// away from the surface, and the two caps meeting along the planes' common line would place
/// the surface's crossing at different points (a seam that cannot close). One pass, in segment
/// order (deterministic); metres.
std::vector<CutSegment> merge_collinear_segments(const std::vector<CutSegment>& segments,
                                                 double tolerance_m, double max_length_m,
                                                 const std::vector<Plane>& split_planes = {});

}  // namespace cutaway
