#include "model/template_checks.h"

#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "base/constants.h"
#include "model/curves.h"

namespace cutaway {

namespace {

std::string degrees(double rad) {
  std::ostringstream s;
  s.precision(4);
  s << rad * 180 / kPi;
  return s.str();
}

[[noreturn]] void fail_at(const FileLoc& loc, const std::string& field, const std::string& rule) {
  throw InputError(loc, field, rule);
}

/// Fewer than 3 distinct points (repeated points do not count) is no curve: the spline and the
/// geometric predicates need them.
void check_distinct(const Polyline2& points, bool closed, const FileLoc& loc,
                    const std::string& field) {
  const size_t n = without_duplicates(points, closed).size();
  if (n < 3) {
    fail_at(loc, field,
            "a curve needs at least 3 distinct points, not " + std::to_string(n) +
                (closed ? " (a closed curve's last point may repeat its first)" : ""));
  }
}

void check_simple(const Polyline2& fitted, bool closed, const FileLoc& loc,
                  const std::string& field, bool smooth) {
  if (auto hit = find_self_intersection(fitted, closed)) {
    fail_at(loc, field,
            std::string("the curve intersects itself") +
                (smooth ? " (as a smooth spline; set smooth: false or move points apart)" : ""));
  }
}

/// The rules of one section loop of an 'around' surface: distinct points, simple, round the
/// axis, star-shaped about it.
void check_around_section(const SurfaceSpec& s, const SectionSpec& section,
                          const std::string& sfield) {
  if (section.circle) return;
  check_distinct(section.loops[0], true, section.loc, sfield);
  const Polyline2 loop = fit_curve(section.loops[0], true, s.smooth);
  check_simple(loop, true, section.loc, sfield, s.smooth);
  if (winding_number(loop, {0, 0}) == 0) {
    fail_at(section.loc, sfield,
            "an 'around' section loop must surround the axis (the point "
            "[0, 0])");
  }
  // Star-shaped about the axis: the angle turns the same way at every step.
  int sign = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const glm::dvec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    const double d = wrap_angle(horizontal_angle(b) - horizontal_angle(a));
    const int sg = d > 1e-12 ? 1 : (d < -1e-12 ? -1 : 0);
    if (sg == 0 || (sign != 0 && sg != sign)) {
      fail_at(section.loc, sfield,
              "an 'around' section loop must be star-shaped about the axis: every ray from "
              "the axis meets it once");
    }
    sign = sg;
  }
}

void check_around(const SurfaceSpec& s) {
  const std::string field = s.path + ".profile";
  check_distinct(s.profile, false, s.profile_loc, field);
  const Polyline2 prof = fit_curve(s.profile, false, s.smooth);
  check_simple(prof, false, s.profile_loc, field, s.smooth);
  for (size_t i = 1; i + 1 < prof.size(); ++i) {
    if (prof[i].x <= 0) {
      fail_at(s.profile_loc, field,
              "the profile touches or crosses the axis between its end points" +
                  std::string(s.smooth ? " (the smooth spline overshoots; add points or set "
                                         "smooth: false)"
                                       : ""));
    }
  }
  if (s.is_skin && (s.profile.front().x != 0 || s.profile.back().x != 0)) {
    fail_at(s.profile_loc, field,
            "the skin must be closed: an 'around' skin's profile starts and ends on the axis "
            "(r = 0)");
  }
  if (s.sections.empty()) {
    check_around_section(s, s.section, s.path + ".section");
    return;
  }
  for (size_t k = 0; k < s.sections.size(); ++k)
    check_around_section(s, s.sections[k].section,
                         s.path + ".sections[" + std::to_string(k) + "].section");
}

/// The rules of one section of a 'within' surface: each loop has distinct points, is simple
/// and lies strictly inside its fold (one loop: fold 0's).
void check_within_section(const SectionSpec& section, bool smooth, const Template& t,
                          const std::string& sfield) {
  for (size_t k = 0; k < section.loops.size(); ++k) {
    const std::string lf =
        section.loops.size() > 1 ? sfield + "[" + std::to_string(k) + "]" : sfield;
    check_distinct(section.loops[k], true, section.loc, lf);
    const Polyline2 loop = fit_curve(section.loops[k], true, smooth);
    check_simple(loop, true, section.loc, lf, smooth);
    const auto [span_lo, span_hi] = fold_span(t, static_cast<int>(k));
    const double centre = t.fold_angles[k];
    for (const auto& p : loop) {
      const double rel = wrap_angle(horizontal_angle(p) - centre);
      if (glm::length(p) < 1e-12 || rel <= span_lo - centre || rel >= span_hi - centre) {
        fail_at(section.loc, lf,
                "a 'within' loop must lie inside fold " + std::to_string(k) + " (angles " +
                    degrees(span_lo) + " to " + degrees(span_hi) + " degrees); a point is at " +
                    degrees(horizontal_angle(p)) + " degrees");
      }
    }
  }
}

void check_within(const SurfaceSpec& s, const Template& t) {
  const std::string field = s.path + ".profile";
  check_distinct(s.profile, true, s.profile_loc, field);
  const Polyline2 prof = fit_curve(s.profile, true, s.smooth);
  check_simple(prof, true, s.profile_loc, field, s.smooth);
  for (const auto& p : prof) {
    if (p.x <= 0) {
      fail_at(s.profile_loc, field, "a 'within' profile must stay off the axis (r > 0)");
    }
  }
  // Between its lowest and highest points, each side must rise monotonically (a rail r(y)).
  size_t lo = 0, hi = 0;
  for (size_t i = 0; i < prof.size(); ++i) {
    if (prof[i].y < prof[lo].y) lo = i;
    if (prof[i].y > prof[hi].y) hi = i;
  }
  const double tol = 1e-9 * (prof[hi].y - prof[lo].y);
  for (int dir : {1, -1}) {
    const long n = static_cast<long>(prof.size());
    for (long i = static_cast<long>(lo); i != static_cast<long>(hi);) {
      const long j = ((i + dir) % n + n) % n;
      if (prof[j].y < prof[i].y - tol) {
        fail_at(s.profile_loc, field,
                "a 'within' profile must rise monotonically on both sides from its lowest to "
                "its highest point");
      }
      i = j;
    }
  }
  if (s.sections.empty()) {
    check_within_section(s.section, s.smooth, t, s.path + ".section");
    return;
  }
  for (size_t k = 0; k < s.sections.size(); ++k)
    check_within_section(s.sections[k].section, s.smooth, t,
                         s.path + ".sections[" + std::to_string(k) + "].section");
}

/// The spine (doc/template-format.md, `spine`): only for swept templates, and rising all the
/// way (its points and the curve fitted through them), so that it neither doubles back nor
/// crosses itself.
void check_spine(const Template& t) {
  const SpineSpec& spine = t.spine;
  if (spine.points.empty()) return;
  if (t.symmetry == Symmetry::None)
    fail_at(spine.loc, "spine", "a spine bends swept surfaces; symmetry none has none");
  for (size_t i = 1; i < spine.points.size(); ++i) {
    if (!(spine.points[i].y > spine.points[i - 1].y))
      fail_at(spine.loc, "spine",
              "each point must lie higher than the one before it (point " + std::to_string(i) +
                  " does not): a spine rises from the bottom of the object to its top");
  }
  const Polyline2 fitted = fit_curve(spine.points, false, true);
  for (size_t i = 1; i < fitted.size(); ++i) {
    if (!(fitted[i].y > fitted[i - 1].y))
      fail_at(spine.loc, "spine",
              "the spline through the points turns downwards between two of them; move or add "
              "points so that it keeps rising");
  }
}

}  // namespace

double wrap_angle(double a) {
  a = std::remainder(a, 2 * kPi);  // not a loop: fold angles may be huge
  return a <= -kPi ? a + 2 * kPi : a;
}

double horizontal_angle(const glm::dvec2& xz) { return std::atan2(-xz.y, xz.x); }

std::pair<double, double> fold_span(const Template& t, int k) {
  const int n = static_cast<int>(t.fold_angles.size());
  if (n <= 1) return {-kPi, kPi};
  const double c = t.fold_angles[k];
  const double prev = k > 0 ? t.fold_angles[k - 1] : t.fold_angles[n - 1] - 2 * kPi;
  const double next = k + 1 < n ? t.fold_angles[k + 1] : t.fold_angles[0] + 2 * kPi;
  return {(prev + c) / 2, (c + next) / 2};
}

void check_template_curves(const Template& t) {
  for (const auto& s : t.surfaces) {
    if (s.kind == SurfaceKind::Around) check_around(s);
    if (s.kind == SurfaceKind::Within) check_within(s, t);
  }
  check_spine(t);
}

}  // namespace cutaway
