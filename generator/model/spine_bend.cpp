#include "model/spine_bend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <glm/geometric.hpp>

#include "base/error.h"
#include "model/curves.h"

namespace cutaway {

namespace {

/// Sample intervals along the fitted spine: fine enough that the piecewise blend between them
/// is smooth to well under a template's edge length (a 200 mm spine: 0.1 mm steps).
constexpr int kSpineIntervals = 2048;
/// Samples a tangent or the turn of the normal is measured over, on each side: a baseline of a
/// few tenths of a millimetre on a fruit-sized spine, long enough that the spline's own
/// sampling does not show as curvature.
constexpr size_t kStencil = 4;
/// The least stretch along the axis a bent vertex may get (SpineBend::stretch): below it the
/// inside of the bend is squeezed to under a fifth of its length, close to folding over.
constexpr double kMinStretch = 0.2;

glm::dvec2 normal_of(const glm::dvec2& t) { return {t.y, -t.x}; }

}  // namespace

SpineBend::SpineBend(const SpineSpec& spine) {
  // The spline sampled much more finely than the intervals, so that its polyline's corners are
  // far below what the stencil resolves.
  const Polyline2 through = without_duplicates(spine.points, false);
  const int per_segment =
      std::max(64, 8 * kSpineIntervals / std::max(1, static_cast<int>(through.size()) - 1));
  const Polyline2 curve = catmull_rom(through, false, per_segment);
  point_ = resample_uniform(curve, false, kSpineIntervals + 1);
  y0_ = spine.points.front().y;
  step_ = curve_length(curve, false) / kSpineIntervals;
  const size_t n = point_.size();
  auto stencil = [n](size_t i) {
    return std::pair<size_t, size_t>{i < kStencil ? 0 : i - kStencil,
                                     std::min(i + kStencil, n - 1)};
  };
  tangent_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const auto [a, b] = stencil(i);
    tangent_[i] = glm::normalize(point_[b] - point_[a]);
  }
  turn_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const auto [a, b] = stencil(i);
    const glm::dvec2 dn =
        (normal_of(tangent_[b]) - normal_of(tangent_[a])) / (step_ * static_cast<double>(b - a));
    turn_[i] = glm::dot(dn, tangent_[i]);
  }
}

std::pair<size_t, double> SpineBend::locate(double s) const {
  const double u = std::clamp(s / step_, 0.0, static_cast<double>(kSpineIntervals));
  const size_t i = std::min(static_cast<size_t>(u), static_cast<size_t>(kSpineIntervals - 1));
  return {i, u - static_cast<double>(i)};
}

std::pair<glm::dvec2, glm::dvec2> SpineBend::frame(double s) const {
  const double length = step_ * kSpineIntervals;
  if (s <= 0 || s >= length) {
    // Beyond an end: straight on along that end's tangent.
    const size_t e = s <= 0 ? 0 : point_.size() - 1;
    const glm::dvec2 t = tangent_[e];
    return {point_[e] + t * (s <= 0 ? s : s - length), t};
  }
  const auto [i, a] = locate(s);
  return {point_[i] + (point_[i + 1] - point_[i]) * a,
          glm::normalize(tangent_[i] + (tangent_[i + 1] - tangent_[i]) * a)};
}

glm::dvec3 SpineBend::map(const glm::dvec3& p) const {
  const auto [c, t] = frame(p.y - y0_);
  const glm::dvec2 q = c + normal_of(t) * p.x;
  return {q.x, q.y, p.z};
}

Plane SpineBend::cross_plane(double y) const {
  const auto [c, t] = frame(y - y0_);
  return {{c.x, c.y, 0.0}, {t.x, t.y, 0.0}};
}

double SpineBend::stretch(const glm::dvec3& p) const {
  const double s = p.y - y0_;
  if (s <= 0 || s >= step_ * kSpineIntervals) return 1.0;
  const auto [i, a] = locate(s);
  return 1.0 + p.x * (turn_[i] + (turn_[i + 1] - turn_[i]) * a);
}

void bend_model(const Template& tmpl, DsModel& model) {
  if (tmpl.spine.points.empty()) return;
  const auto shared = std::make_shared<const SpineBend>(tmpl.spine);
  const SpineBend& bend = *shared;
  for (const DsSurface& surface : model.surfaces) {
    for (auto vh : surface.mesh.vertices()) {
      const auto& q = surface.mesh.point(vh);
      const glm::dvec3 p(q[0], q[1], q[2]);
      if (bend.stretch(p) >= kMinStretch) continue;
      char text[320];
      const double units = 1.0 / tmpl.metres_per_unit;  // template units per metre
      std::snprintf(text, sizeof text,
                    "bends more tightly than the object is thick: surface '%s' reaches %.4g "
                    "from the axis at height %.4g, where the spine's radius of curvature is "
                    "only %.4g (template units); make the bend gentler there",
                    surface.name.c_str(), std::fabs(p.x) * units, p.y * units,
                    std::fabs(p.x) / (1.0 - bend.stretch(p)) * units);
      throw InputError(tmpl.spine.loc, "spine", text);
    }
  }
  for (DsSurface& surface : model.surfaces) {
    for (auto vh : surface.mesh.vertices()) {
      const auto& q = surface.mesh.point(vh);
      const glm::dvec3 b = bend.map({q[0], q[1], q[2]});
      surface.mesh.set_point(vh, DsMesh::Point(b.x, b.y, b.z));
    }
  }
  model.bent_axis = BentAxis{shared, model.bbox_min.y, model.bbox_max.y};
  update_bounds(model);
}

}  // namespace cutaway
