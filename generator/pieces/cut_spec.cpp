#include "pieces/cut_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "base/constants.h"
#include "base/error.h"
#include "model/mesh_surface.h"
#include "model/template.h"

namespace cutaway {

namespace {

/// The radius of a closed star-shaped loop ([x, z] points) along +X: where its edges cross the
/// ray z = 0, x > 0 (the farthest crossing); 0 when none does.
double radius_at_angle_zero(const std::vector<glm::dvec2>& loop) {
  double best = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const glm::dvec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    if ((a.y > 0) == (b.y > 0)) {
      if (a.y == 0 && a.x > 0) best = std::max(best, a.x);
      continue;
    }
    const double t = a.y / (a.y - b.y);
    const double x = a.x + t * (b.x - a.x);
    if (x > 0) best = std::max(best, x);
  }
  return best;
}

/// Largest radius of the section loop over its radius at angle 0 (1 for a circle).
double section_reach(const SectionSpec& section) {
  if (section.circle || section.loops.empty()) return 1.0;
  const auto& loop = section.loops.front();
  double far = 0;
  for (const auto& p : loop) far = std::max(far, std::hypot(p.x, p.y));
  const double r0 = radius_at_angle_zero(loop);
  return r0 > 0 ? far / r0 : 1.5;
}

void add_bounds(const MeshBounds& b, ObjectExtents& e, double& lo, double& hi) {
  const double x = std::max(std::fabs(b.min.x), std::fabs(b.max.x));
  const double z = std::max(std::fabs(b.min.z), std::fabs(b.max.z));
  e.radius_m = std::max(e.radius_m, std::hypot(x, z));
  lo = std::min(lo, b.min.y);
  hi = std::max(hi, b.max.y);
}

long long ceil_count(double length, double step) {
  const double n = std::ceil(length / step - 1e-9);
  return static_cast<long long>(std::clamp(n, 1.0, 1e9));
}

}  // namespace

std::string cut_label(const CutSpec& cut) {
  auto mm = [](double metres) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", metres * 1000);
    std::string s = text;
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    return s + "mm";
  };
  switch (cut.type) {
    case CutType::Whole: return "whole";
    case CutType::Halves: return "halves";
    case CutType::Slices: return "slices:" + mm(cut.thickness_m);
    case CutType::Wedges: return "wedges:" + std::to_string(cut.count);
    case CutType::Dice: return "dice:" + mm(cut.size_m);
    case CutType::Plane: return "plane";
  }
  return "whole";
}

std::string cut_exact_text(const CutSpec& cut) {
  char numbers[256];
  const Plane& p = cut.plane;
  std::snprintf(numbers, sizeof numbers, " %.17g %.17g %d %.17g %.17g %.17g %.17g %.17g %.17g",
                cut.thickness_m, cut.size_m, cut.count, p.point.x, p.point.y, p.point.z, p.normal.x,
                p.normal.y, p.normal.z);
  return cut_label(cut) + numbers;
}

ObjectExtents template_extents(const Template& t) {
  ObjectExtents e;
  if (t.skin >= 0 && t.surfaces[t.skin].kind != SurfaceKind::Mesh) {
    const SurfaceSpec& skin = t.surfaces[t.skin];
    double max_r = 0, lo = skin.profile.front().y, hi = lo;
    for (const auto& p : skin.profile) {
      max_r = std::max(max_r, p.x);
      lo = std::min(lo, p.y);
      hi = std::max(hi, p.y);
    }
    // A spine moves the axis sideways by at most its points' reach (the spline through them
    // stays close to it); the height along the straight axis bounds the bent one.
    double spine_reach = 0;
    for (const auto& p : t.spine.points) spine_reach = std::max(spine_reach, std::fabs(p.x));
    double reach = section_reach(skin.section);
    for (const HeightSection& h : skin.sections) reach = std::max(reach, section_reach(h.section));
    e.radius_m = max_r * reach + spine_reach;
    e.height_m = hi - lo;
    return e;
  }
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < t.surfaces.size(); ++i) {
    const SurfaceSpec& s = t.surfaces[i];
    if (s.kind != SurfaceKind::Mesh) continue;
    if (t.skin >= 0 && static_cast<int>(i) != t.skin) continue;
    add_bounds(mesh_bounds(*s.mesh, t.metres_per_unit), e, lo, hi);
  }
  e.height_m = hi > lo ? hi - lo : 0;
  return e;
}

Check check_cap_texels(double cut_area_m2, double texels_per_mm) {
  const double texels = cut_area_m2 * (1000 * texels_per_mm) * (1000 * texels_per_mm);
  if (texels <= kMaxCapTexels) return {};
  char text[200];
  std::snprintf(text, sizeof text,
                "at %g texels per mm the cut faces would need about %.3g M texels (at most %g M): "
                "lower texels_per_mm or cut fewer or smaller objects",
                texels_per_mm, texels / 1e6, kMaxCapTexels / 1e6);
  return Check::none(text);
}

double fitting_texels_per_mm(double cut_area_m2, double wanted) {
  if (check_cap_texels(cut_area_m2, wanted)) return wanted;
  // texels = area (1000 d)^2 <= kMaxCapTexels; the tenths rounded down, one less while the
  // rounding of the root still lets the check fail.
  double tenths = std::floor(10 * std::sqrt(kMaxCapTexels / cut_area_m2) / 1000);
  while (tenths >= 1 && !check_cap_texels(cut_area_m2, tenths / 10)) tenths -= 1;
  return tenths >= 1 ? tenths / 10 : 0.0;
}

double estimate_object_volume(const ObjectExtents& extents) {
  return 2.0 / 3.0 * kPi * extents.radius_m * extents.radius_m * extents.height_m;
}

double estimate_cut_area(const CutSpec& cut, const ObjectExtents& extents) {
  const double r = extents.radius_m, h = extents.height_m;
  const double any_plane = 2 * r * std::sqrt(h * h + 4 * r * r);
  const double across = kPi * r * r;  // a plane across the axis
  double area = 0;
  switch (cut.type) {
    case CutType::Whole: break;
    case CutType::Halves:
    case CutType::Plane: area = 2 * any_plane; break;
    case CutType::Wedges: area = 2 * cut.count * r * h; break;
    case CutType::Slices: area = 2 * (estimate_piece_count(cut, extents) - 1) * across; break;
    case CutType::Dice: {
      const double sides = static_cast<double>(ceil_count(2 * r, cut.size_m)) - 1;
      const double layers = static_cast<double>(ceil_count(h, cut.size_m)) - 1;
      area = 2 * (2 * sides * 2 * r * h + layers * across);
      break;
    }
  }
  return std::min(area, 1e12);
}

long long estimate_piece_count(const CutSpec& cut, const ObjectExtents& extents) {
  switch (cut.type) {
    case CutType::Whole: return 1;
    case CutType::Halves:
    case CutType::Plane: return 2;
    case CutType::Wedges: return cut.count;
    case CutType::Slices: return ceil_count(extents.height_m, cut.thickness_m) + 1;
    case CutType::Dice: {
      const double across = static_cast<double>(ceil_count(2 * extents.radius_m, cut.size_m));
      const double along = static_cast<double>(ceil_count(extents.height_m, cut.size_m));
      const double n = across * across * along;
      return static_cast<long long>(std::min(n, 1e9));
    }
  }
  return 1;
}

}  // namespace cutaway
