#include "pieces/cut_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "base/constants.h"
#include "base/error.h"
#include "io/plane_spec.h"
#include "io/text_rules.h"
#include "model/mesh_import.h"
#include "model/template.h"

namespace cutaway {

namespace {

const char* const kForms =
    "write whole, halves, slices:THICKNESS, wedges:COUNT, dice:SIZE or plane:SPEC";

/// A positive length in units of `metres_per_unit` as metres, at least kMinCutLength_m.
Outcome<double> parse_cut_length(const std::string& s, const std::string& what,
                                 double metres_per_unit) {
  using R = Outcome<double>;
  const R v = parse_decimal(s, what);
  if (!v) return v;
  if (!(*v > 0)) return R::none(what + " must be positive, not " + quoted(s));
  const double m = *v * metres_per_unit;
  if (!std::isfinite(m)) return R::none(what + " is too large: " + quoted(s));
  if (m < kMinCutLength_m * (1 - 1e-9))  // 0.05 cm is 0.5 mm too
    return R::none(what + " must be at least 0.5 mm, not " + quoted(s));
  return m;
}

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
    case CutType::Whole:
      return "whole";
    case CutType::Halves:
      return "halves";
    case CutType::Slices:
      return "slices:" + mm(cut.thickness_m);
    case CutType::Wedges:
      return "wedges:" + std::to_string(cut.count);
    case CutType::Dice:
      return "dice:" + mm(cut.size_m);
    case CutType::Plane:
      return "plane";
  }
  return "whole";
}

Outcome<CutSpec> parse_cut_spec(const std::string& text, double metres_per_unit) {
  using R = Outcome<CutSpec>;
  CutSpec cut;
  const size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  const bool has_arg = colon != std::string::npos;
  const std::string arg = has_arg ? text.substr(colon + 1) : "";
  if (kind == "whole" || kind == "halves") {
    if (has_arg) return R::none(quoted(text) + ": '" + kind + "' takes no value");
    cut.type = kind == "whole" ? CutType::Whole : CutType::Halves;
    return cut;
  }
  if (kind == "slices" || kind == "wedges" || kind == "dice" || kind == "plane") {
    if (!has_arg || arg.empty()) {
      const char* value = kind == "slices" ? "THICKNESS" : kind == "wedges" ? "COUNT"
                          : kind == "dice" ? "SIZE" : "SPEC";
      return R::none(quoted(text) + ": write " + kind + ":" + value);
    }
  }
  if (kind == "slices") {
    cut.type = CutType::Slices;
    const Outcome<double> thickness = parse_cut_length(arg, "the slice thickness", metres_per_unit);
    if (!thickness) return R::none(thickness.reason());
    cut.thickness_m = *thickness;
    return cut;
  }
  if (kind == "dice") {
    cut.type = CutType::Dice;
    const Outcome<double> size = parse_cut_length(arg, "the dice size", metres_per_unit);
    if (!size) return R::none(size.reason());
    cut.size_m = *size;
    return cut;
  }
  if (kind == "wedges") {
    const Outcome<double> n = parse_decimal(arg, "the wedge count");
    if (!n) return R::none(n.reason());
    if (*n != std::floor(*n) || *n < 2 || *n > 64)
      return R::none("the wedge count must be a whole number from 2 to 64, not " + quoted(arg));
    cut.type = CutType::Wedges;
    cut.count = static_cast<int>(*n);
    return cut;
  }
  if (kind == "plane") {
    cut.type = CutType::Plane;
    const Outcome<Plane> plane = parse_plane_spec(arg, metres_per_unit);
    if (!plane) return R::none(plane.reason());
    cut.plane = *plane;
    return cut;
  }
  return R::none(quoted(text) + " is not a cut: " + kForms);
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
    e.radius_m = max_r * section_reach(skin.section);
    e.height_m = hi - lo;
    return e;
  }
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < t.surfaces.size(); ++i) {
    const SurfaceSpec& s = t.surfaces[i];
    if (s.kind != SurfaceKind::Mesh) continue;
    if (t.skin >= 0 && static_cast<int>(i) != t.skin) continue;
    add_bounds(read_mesh_bounds(s.mesh_file, t.metres_per_unit, s.mesh_loc, s.path + ".file"), e,
               lo, hi);
  }
  e.height_m = hi > lo ? hi - lo : 0;
  return e;
}

std::string cap_texels_rule(double cut_area_m2, double texels_per_mm) {
  const double texels = cut_area_m2 * (1000 * texels_per_mm) * (1000 * texels_per_mm);
  if (texels <= kMaxCapTexels) return "";
  char text[200];
  std::snprintf(text, sizeof text,
                "at %g texels per mm the cut faces would need about %.3g M texels (at most %g M): "
                "lower texels_per_mm or cut fewer or smaller objects",
                texels_per_mm, texels / 1e6, kMaxCapTexels / 1e6);
  return text;
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
