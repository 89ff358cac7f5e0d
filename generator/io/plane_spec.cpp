#include "io/plane_spec.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <glm/geometric.hpp>

#include "base/error.h"
#include "io/text_rules.h"

namespace cutaway {

namespace {

/// `text` split at every `sep` (empty parts kept).
std::vector<std::string_view> split(std::string_view text, char sep) {
  std::vector<std::string_view> parts;
  size_t begin = 0;
  while (true) {
    const size_t at = text.find(sep, begin);
    parts.push_back(text.substr(begin, at == std::string_view::npos ? text.npos : at - begin));
    if (at == std::string_view::npos) return parts;
    begin = at + 1;
  }
}

/// A coordinate in template units as metres; refused when it leaves the double range.
Outcome<double> to_metres(std::string_view text, const char* what, double metres_per_unit) {
  const Outcome<double> v = parse_decimal(text, what);
  if (!v) return v;
  const double m = *v * metres_per_unit;
  if (!std::isfinite(m)) return Outcome<double>::none(std::string(what) + " is too large");
  return m;
}

}  // namespace

Outcome<Plane> parse_plane_spec(const std::string& spec, double metres_per_unit) {
  using R = Outcome<Plane>;
  const std::string_view s = trim_blanks(spec);
  const auto not_a_plane = [&] {
    return R::none(quoted(spec) + " is not a plane: write AXIS=VALUE (e.g. y=20) or "
                                  "px,py,pz/nx,ny,nz (a point and a normal, template units)");
  };
  Plane plane;
  if (const size_t eq = s.find('='); eq != std::string_view::npos) {
    const std::string_view axis_text = trim_blanks(s.substr(0, eq));
    if (axis_text.size() != 1 || std::string_view("xyzXYZ").find(axis_text[0]) == s.npos)
      return not_a_plane();
    const int axis = std::tolower(axis_text[0]) - 'x';
    plane.point = glm::dvec3(0.0);
    const Outcome<double> at =
        to_metres(s.substr(eq + 1), "the plane's coordinate", metres_per_unit);
    if (!at) return R::none(at.reason());
    plane.point[axis] = *at;
    plane.normal = glm::dvec3(0.0);
    plane.normal[axis] = 1;
    return plane;
  }
  const auto halves = split(s, '/');
  if (halves.size() != 2) return not_a_plane();
  const auto point = split(halves[0], ','), normal = split(halves[1], ',');
  if (point.size() != 3 || normal.size() != 3) return not_a_plane();
  for (int k = 0; k < 3; ++k) {
    const Outcome<double> p = to_metres(point[k], "a point coordinate", metres_per_unit);
    if (!p) return R::none(p.reason());
    const Outcome<double> n = parse_decimal(normal[k], "a normal component");
    if (!n) return R::none(n.reason());
    plane.point[k] = *p;
    plane.normal[k] = *n;
  }
  // Scale by the largest component first, so that tiny (even subnormal) normals normalise.
  const double largest =
      std::max({std::fabs(plane.normal.x), std::fabs(plane.normal.y), std::fabs(plane.normal.z)});
  if (!(largest > 0)) return R::none(quoted(spec) + ": the plane's normal must not be zero");
  plane.normal = glm::normalize(plane.normal / largest);
  return plane;
}

}  // namespace cutaway
