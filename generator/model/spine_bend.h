// The bent axis (doc/template-format.md, `spine`): a template is swept about a straight +Y axis
// and the whole DS model is then carried onto a curve in the profile plane, so a banana, a
// carrot or a zucchini keeps every surface, sheet and grain in the same place relative to the
// others (the colour inside is bent with them; cuts stay consistent because they cut the bent
// surfaces).
#pragma once

#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/plane.h"
#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// The map from the straight frame to the bent one. A point (x, y, z) of the straight model
/// goes to C(s) + x N(s) + z Z, where C is the spine (the centripetal Catmull-Rom spline
/// through its points, as for profiles; a spine is always smooth: a corner would tear the
/// surfaces apart on its outside and fold them on its inside) at arc
/// length s = y - y0 from its first point (y0: that point's height), N(s) its unit normal in the
/// profile plane (the tangent turned clockwise, +X for a spine along +Y) and Z = (0, 0, 1).
/// Beyond the spine's ends the curve goes on along its end tangents. A spine that is a vertical
/// line through the axis maps every point onto itself.
class SpineBend {
 public:
  /// @pre spine.points has at least 2 distinct points (the parser asks for 3)
  explicit SpineBend(const SpineSpec& spine);

  /// The bent position of straight-frame point `p` (metres).
  glm::dvec3 map(const glm::dvec3& p) const;

  /// The bent image of the straight frame's plane y = `y` (metres): the plane through the
  /// spine's point C(y - y0) whose normal is the spine's unit tangent there (pointing along
  /// increasing y), the plane a cut across a bent object follows.
  Plane cross_plane(double y) const;

  /// How much the map stretches lengths along the axis at straight-frame point `p`:
  /// 1 + x dot(dN/ds, T) (1 on a straight stretch, 0 where the inside of a bend folds over).
  double stretch(const glm::dvec3& p) const;

 private:
  /// Index of the sample interval holding arc length s (clamped) and the blend in it.
  std::pair<size_t, double> locate(double s) const;
  /// The spine's point and unit tangent at arc length s (beyond an end: along its tangent).
  std::pair<glm::dvec2, glm::dvec2> frame(double s) const;

  double y0_ = 0, step_ = 0;
  std::vector<glm::dvec2> point_, tangent_;
  std::vector<double> turn_;  ///< dot(dN/ds, T) per sample (the signed curvature, negated)
};

/// Bends every surface of `model` onto tmpl.spine (no-op without one), updates its bounds and
/// sets model.bent_axis (the bend and the straight model's height range).
/// @throws InputError at `spine` where the spine bends more tightly than the object is thick
///         (some vertex of the model would be stretched by less than 0.2 along the axis), so
///         the bent surfaces could fold over or cross each other
void bend_model(const Template& tmpl, DsModel& model);

}  // namespace cutaway
