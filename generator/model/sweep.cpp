#include "model/sweep.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "base/constants.h"
#include "model/curves.h"
#include "model/template_checks.h"

namespace cutaway {

namespace {

/// Row-major grid of vertices; a row of one vertex is a pole.
struct SweepGrid {
  std::vector<std::vector<glm::dvec3>> rows;
  std::vector<std::vector<glm::dvec2>> params;  // (t_profile, t_section) per vertex
  bool open_rows = false;  // rows end where they start (a `span`): no face joins last to first
};

/// Refuses a surface of rows x cols vertices (at least) beyond the `max_vertices` left of the
/// model's budget, before it is sampled.
void check_vertex_budget(size_t rows, size_t cols, const SurfaceSpec& spec, const Template& t,
                         size_t max_vertices) {
  if (rows * cols > max_vertices) {
    const size_t taken = kMaxModelVertices - std::min(max_vertices, kMaxModelVertices);
    throw InputError(
        t.edge_loc, "resolution.edge",
        "the edge length is too small: surface " + quoted(spec.name) + " would get at least " +
            std::to_string(rows * cols) + " vertices, and the model may have at most " +
            std::to_string(kMaxModelVertices) + " over all surfaces" +
            (taken > 0 ? " (" + std::to_string(taken) + " taken by the surfaces before it)" : ""));
  }
}

int segments_for(double length_m, double edge_m, int minimum) {
  const double n = std::ceil(length_m / edge_m);
  return static_cast<int>(std::clamp(n, static_cast<double>(minimum), 1e7));
}

/// Appends the grid's triangles to `faces` with vertex indices offset by `base`; rows are
/// closed loops of equal length (or open ones when g.open_rows), or poles. Winding: (i,j) ->
/// (i,j+1) -> (i+1,j+1).
void grid_faces(const SweepGrid& g, std::vector<int>& index_of_row,
                std::vector<std::array<int, 3>>& faces) {
  for (size_t i = 0; i + 1 < g.rows.size(); ++i) {
    const auto& a = g.rows[i];
    const auto& b = g.rows[i + 1];
    const size_t m = std::max(a.size(), b.size());
    for (size_t j = 0; j < (g.open_rows ? m - 1 : m); ++j) {
      const size_t j1 = (j + 1) % m;
      auto va = [&](size_t k) { return index_of_row[i] + static_cast<int>(a.size() == 1 ? 0 : k); };
      auto vb = [&](size_t k) {
        return index_of_row[i + 1] + static_cast<int>(b.size() == 1 ? 0 : k);
      };
      if (a.size() > 1) faces.push_back({va(j), va(j1), vb(j1)});
      if (b.size() > 1) faces.push_back({va(j), vb(j1), vb(j)});
    }
  }
}

/// Adds one grid's vertices (with DS attributes) and faces to `mesh`. Flips the winding when
/// `flip`.
void add_grid(const SweepGrid& g, const SurfaceSpec& spec, double ripeness, bool flip,
              DsMesh& mesh) {
  std::vector<DsMesh::VertexHandle> vh;
  std::vector<int> index_of_row;
  for (size_t i = 0; i < g.rows.size(); ++i) {
    index_of_row.push_back(static_cast<int>(vh.size()));
    for (size_t j = 0; j < g.rows[i].size(); ++j) {
      const glm::dvec3& p = g.rows[i][j];
      const glm::dvec2& t = g.params[i][j];
      auto h = mesh.add_vertex(DsMesh::Point(p.x, p.y, p.z));
      auto& d = mesh.data(h);
      const glm::dvec3 f = spec.front.at(t.x, t.y, ripeness);
      const glm::dvec3 b = spec.back.at(t.x, t.y, ripeness);
      d.front = {f.x, f.y, f.z};
      d.back = {b.x, b.y, b.z};
      d.blur = vertex_blur(spec.blur.at(t.x, t.y, ripeness));
      d.param = {t.x, t.y};
      vh.push_back(h);
    }
  }
  std::vector<std::array<int, 3>> faces;
  grid_faces(g, index_of_row, faces);
  for (auto f : faces) {
    if (flip) std::swap(f[1], f[2]);
    const auto fh = mesh.add_face(vh[f[0]], vh[f[1]], vh[f[2]]);
    CUTAWAY_CHECK(fh.is_valid());
  }
}

/// Signed volume enclosed by a closed grid (positive when its normals point outwards).
double grid_volume(const SweepGrid& g) {
  std::vector<glm::dvec3> pts;
  std::vector<int> index_of_row;
  for (const auto& row : g.rows) {
    index_of_row.push_back(static_cast<int>(pts.size()));
    pts.insert(pts.end(), row.begin(), row.end());
  }
  std::vector<std::array<int, 3>> faces;
  grid_faces(g, index_of_row, faces);
  double v = 0;
  for (const auto& f : faces) v += glm::dot(pts[f[0]], glm::cross(pts[f[1]], pts[f[2]])) / 6.0;
  return v;
}

/// Fitted closed section loop in the XZ plane, turned so that its angle about the axis
/// increases (counter-clockwise seen from +Y) and started where it crosses angle 0.
Polyline2 around_loop_from_angle0(const Polyline2& fitted) {
  Polyline2 loop = fitted;
  // Angle increases from +X towards -Z: counter-clockwise in the (x, -z) plane.
  Polyline2 flipped;
  for (const auto& p : loop) flipped.push_back({p.x, -p.y});
  if (signed_area(flipped) < 0) std::reverse(loop.begin(), loop.end());
  const size_t n = loop.size();
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec2 a = loop[i], b = loop[(i + 1) % n];
    // Crossing of the +X half-axis (angle 0): -z goes from below 0 to >= 0 with x > 0.
    if (-a.y < 0 && -b.y >= 0) {
      const double s = (-a.y) / ((-a.y) - (-b.y));
      const glm::dvec2 c = a + (b - a) * s;
      if (c.x <= 0) continue;
      Polyline2 out{c};
      for (size_t k = 1; k <= n; ++k) {
        const glm::dvec2 q = loop[(i + k) % n];
        if (glm::distance(q, c) > 1e-12) out.push_back(q);
      }
      return out;
    }
  }
  CUTAWAY_CHECK(!"section loop does not cross angle 0");
  return loop;
}

/// A y-monotonic rail of a `within` profile: r and the closed profile's parameter as
/// functions of height, by linear interpolation.
struct Rail {
  std::vector<double> y, r, t, s;  // s: normalised arc length along the rail

  double at(const std::vector<double>& v, double yq) const {
    if (yq <= y.front()) return v.front();
    if (yq >= y.back()) return v.back();
    const size_t i = static_cast<size_t>(std::upper_bound(y.begin(), y.end(), yq) - y.begin());
    const double y0 = y[i - 1], y1 = y[i];
    const double a = y1 > y0 ? (yq - y0) / (y1 - y0) : 1.0;
    return v[i - 1] + (v[i] - v[i - 1]) * a;
  }
};

/// The closed 'within' profile split at its lowest and highest points into two rails, both
/// running upward: the inner one (smaller mean radius) and the outer one, their y made
/// monotonic and their arc length normalised to 0..1.
struct WithinRails {
  Polyline2 profile;          ///< counter-clockwise in (r, y), from its lowest point
  std::vector<double> tprof;  ///< arc-length parameter of each profile point
  size_t top = 0;             ///< index of the highest profile point
  Rail inner, outer;
  double mean_length = 0;  ///< the rails' mean length, metres
};

WithinRails within_rails(const SurfaceSpec& spec) {
  WithinRails w;
  Polyline2& prof = w.profile;
  prof = fit_curve(spec.profile, true, spec.smooth);
  if (signed_area(prof) < 0) std::reverse(prof.begin(), prof.end());
  size_t lo = 0;
  for (size_t i = 0; i < prof.size(); ++i)
    if (prof[i].y < prof[lo].y) lo = i;
  std::rotate(prof.begin(), prof.begin() + static_cast<long>(lo), prof.end());
  w.tprof = arc_length_parameters(prof, true);
  size_t& hi = w.top;
  for (size_t i = 0; i < prof.size(); ++i)
    if (prof[i].y > prof[hi].y) hi = i;

  // Rail A: lowest -> highest going forward (counter-clockwise: the outer side first);
  // rail B: lowest -> highest going backward.
  Rail ra, rb;
  for (size_t i = 0; i <= hi; ++i) {
    ra.y.push_back(prof[i].y);
    ra.r.push_back(prof[i].x);
    ra.t.push_back(w.tprof[i]);
  }
  for (size_t k = 0; k + hi <= prof.size(); ++k) {
    const size_t i = k == 0 ? 0 : prof.size() - k;
    rb.y.push_back(prof[i].y);
    rb.r.push_back(prof[i].x);
    rb.t.push_back(k == 0 ? 1.0 : w.tprof[i]);
  }
  for (Rail* rail : {&ra, &rb}) {
    // Enforce monotonic y (plateaus from the checks' tolerance) and arc length per rail.
    for (size_t i = 1; i < rail->y.size(); ++i) rail->y[i] = std::max(rail->y[i], rail->y[i - 1]);
    rail->s.assign(rail->y.size(), 0.0);
    for (size_t i = 1; i < rail->y.size(); ++i) {
      rail->s[i] =
          rail->s[i - 1] + std::hypot(rail->y[i] - rail->y[i - 1], rail->r[i] - rail->r[i - 1]);
    }
  }
  const double len_a = ra.s.back(), len_b = rb.s.back();
  for (auto& v : ra.s) v /= len_a;
  for (auto& v : rb.s) v /= len_b;
  double mean_a = 0, mean_b = 0;
  for (double r : ra.r) mean_a += r / ra.r.size();
  for (double r : rb.r) mean_b += r / rb.r.size();
  w.mean_length = 0.5 * (len_a + len_b);
  w.inner = mean_a < mean_b ? ra : rb;
  w.outer = mean_a < mean_b ? rb : ra;
  return w;
}

/// n + 1 heights from the lowest to the highest profile point, spaced by the mean of both
/// rails' normalised arc length (bisection per height).
std::vector<double> within_heights(const WithinRails& w, int n) {
  const double y_lo = w.profile[0].y, y_hi = w.profile[w.top].y;
  std::vector<double> heights(n + 1);
  heights[0] = y_lo;
  heights[n] = y_hi;
  for (int i = 1; i < n; ++i) {
    const double target = static_cast<double>(i) / n;
    double a = y_lo, b = y_hi;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (a + b);
      const double sm = 0.5 * (w.inner.at(w.inner.s, mid) + w.outer.at(w.outer.s, mid));
      (sm < target ? a : b) = mid;
    }
    heights[i] = 0.5 * (a + b);
  }
  return heights;
}

/// The smallest and largest u (x) of a loop.
std::pair<double, double> u_range(const Polyline2& loop) {
  double umin = loop[0].x, umax = loop[0].x;
  for (const auto& p : loop) {
    umin = std::min(umin, p.x);
    umax = std::max(umax, p.x);
  }
  return {umin, umax};
}

/// Loop `k` of a 'within' section in fold k's frame (u along the fold centre, w towards
/// increasing angle), counter-clockwise in (u, w), started at the largest u.
Polyline2 fold_frame_loop(const SectionSpec& section, bool smooth, const Template& t, size_t k) {
  const double centre = t.fold_angles[k];
  Polyline2 uw;
  for (const auto& p : fit_curve(section.loops[k], true, smooth)) {
    const double rel = horizontal_angle(p) - centre, rho = glm::length(p);
    uw.push_back({rho * std::cos(rel), rho * std::sin(rel)});
  }
  if (signed_area(uw) < 0) std::reverse(uw.begin(), uw.end());
  const auto start =
      std::max_element(uw.begin(), uw.end(), [](auto& a, auto& b) { return a.x < b.x; });
  std::rotate(uw.begin(), start, uw.end());
  return uw;
}

/// The sweep grid of fold `fold`: at each height i, `loops[i]` (m points, fold frame, started
/// at its largest u) stretched in u from the inner to the outer rail and scaled alike in w,
/// rotated to the fold's centre angle; a single point on the inner rail at the lowest and
/// highest height. `blended[i]`: loop i is a blend of two sections, checked here for
/// self-intersection (the sections themselves passed check_template_curves).
/// @throws InputError when a point leaves the fold's angular span or a blended loop crosses
///         itself
SweepGrid within_fold_grid(const SurfaceSpec& spec, const Template& t, const WithinRails& w,
                           const std::vector<double>& heights, const std::vector<Polyline2>& loops,
                           const std::vector<bool>& blended, int fold) {
  const int n = static_cast<int>(heights.size()) - 1;
  const double theta = t.fold_angles[fold];
  const glm::dvec3 centre_dir(std::cos(theta), 0, -std::sin(theta));
  const glm::dvec3 across_dir(-std::sin(theta), 0, -std::cos(theta));
  const auto [span_lo, span_hi] = fold_span(t, fold);
  const std::string field =
      spec.sections.empty() ? spec.path + ".section" : spec.path + ".sections";
  const FileLoc& loc = spec.sections.empty() ? spec.section.loc : spec.sections.front().section.loc;
  SweepGrid g;
  for (int i = 0; i <= n; ++i) {
    const double y = heights[i];
    const double rin = w.inner.at(w.inner.r, y), rout = w.outer.at(w.outer.r, y);
    const double tin = w.inner.at(w.inner.t, y), tout = w.outer.at(w.outer.t, y);
    std::vector<glm::dvec3> row;
    std::vector<glm::dvec2> par;
    if (i == 0 || i == n) {
      row.push_back(centre_dir * rin + glm::dvec3(0, y, 0));
      par.push_back({i == 0 ? 0.0 : w.tprof[w.top], 0});
    } else {
      const Polyline2& loop = loops[static_cast<size_t>(i)];
      const int m = static_cast<int>(loop.size());
      if (blended[static_cast<size_t>(i)] && find_self_intersection(loop, true)) {
        throw InputError(loc, field,
                         "the blend of two sections crosses itself at height " +
                             std::to_string(y / t.metres_per_unit) +
                             ": give a section between them, or make them more alike");
      }
      const auto [umin, umax] = u_range(loop);
      const double k = (rout - rin) / (umax - umin);
      for (int j = 0; j < m; ++j) {
        const double u = rin + (loop[j].x - umin) * k, wv = loop[j].y * k;
        const glm::dvec3 p = centre_dir * u + across_dir * wv + glm::dvec3(0, y, 0);
        const double rel = std::atan2(wv, u);
        if (rel <= span_lo - theta || rel >= span_hi - theta) {
          throw InputError(loc, field,
                           "the swept 'within' surface leaves fold " + std::to_string(fold) +
                               " at height " + std::to_string(y / t.metres_per_unit) +
                               ": make the loop narrower across the fold");
        }
        const double a = (loop[j].x - umin) / (umax - umin);
        row.push_back(p);
        par.push_back({tin + (tout - tin) * a, static_cast<double>(j) / m});
      }
    }
    g.rows.push_back(std::move(row));
    g.params.push_back(std::move(par));
  }
  return g;
}

/// The distance from the origin to the closed polyline `loop` (star-shaped about the origin:
/// template_checks.h) along the ray at angle `phi`, direction (cos phi, -sin phi) (the
/// templates' angle convention: from +X towards -Z). A ray through a corner of the loop meets
/// both of its segments at an end, where rounding may put the crossing a hair outside either:
/// each segment is taken with a margin of 1e-9 of its length, and the farthest crossing wins.
double radius_along(const Polyline2& loop, double phi) {
  const glm::dvec2 d(std::cos(phi), -std::sin(phi));
  double best = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const glm::dvec2 a = loop[i], e = loop[(i + 1) % loop.size()] - a;
    const double den = d.x * e.y - d.y * e.x;
    if (den == 0) continue;
    const double t = (a.x * e.y - a.y * e.x) / den;  // origin + t d = a + u e
    const double u = (a.x * d.y - a.y * d.x) / den;
    if (u >= -1e-9 && u <= 1 + 1e-9 && t > best) best = t;
  }
  CUTAWAY_CHECK(best > 0);  // a star-shaped loop round the origin meets every ray
  return best;
}

/// Which two of `sections` (at increasing heights) a ring at normalised height tp lies between,
/// and the smoothstep weight of the upper one: (k, w) blends sections k and k + 1 as
/// (1 - w) a + w b; below the first and above the last height, w = 0 and k is that section.
std::pair<size_t, double> height_blend(const std::vector<HeightSection>& sections, double tp) {
  size_t k = 0;
  while (k + 1 < sections.size() && sections[k + 1].at <= tp) ++k;
  double w = 0;
  if (k + 1 < sections.size() && tp > sections[k].at) {
    const double x = (tp - sections[k].at) / (sections[k + 1].at - sections[k].at);
    w = x * x * (3 - 2 * x);
  }
  return {k, w};
}

/// A surface's sections from the lowest height up: its one `section`, or each of `sections`.
std::vector<const SectionSpec*> sections_of(const SurfaceSpec& spec) {
  std::vector<const SectionSpec*> out;
  if (spec.sections.empty()) out.push_back(&spec.section);
  for (const HeightSection& h : spec.sections) out.push_back(&h.section);
  return out;
}

/// The unit rings of an 'around' surface sampled at the angles `phis` (from +X towards -Z):
/// per profile sample i of n + 1 (normalised arc length i / n), the point at each angle at the
/// section's radius there over its radius at angle 0. With `sections` at several heights, the
/// radii are blended between the two sections whose heights enclose i / n by a smoothstep
/// (below the first and above the last: that one).
std::vector<Polyline2> unit_rings_at_angles(const SurfaceSpec& spec, int n,
                                            const std::vector<double>& phis) {
  std::vector<std::vector<double>> radii;
  for (const SectionSpec* section : sections_of(spec)) {
    std::vector<double> r(phis.size(), 1.0);
    if (!section->circle) {
      const Polyline2 loop = fit_curve(section->loops[0], true, spec.smooth);
      const double r0 = radius_along(loop, 0);
      for (size_t j = 0; j < phis.size(); ++j) r[j] = radius_along(loop, phis[j]) / r0;
    }
    radii.push_back(std::move(r));
  }
  std::vector<Polyline2> loops;
  for (int i = 0; i <= n; ++i) {
    const auto [k, w] = spec.sections.empty()
                            ? std::pair<size_t, double>{0, 0.0}
                            : height_blend(spec.sections, static_cast<double>(i) / n);
    const std::vector<double>& a = radii[k];
    const std::vector<double>& b = radii[std::min(k + 1, radii.size() - 1)];
    Polyline2 loop;
    for (size_t j = 0; j < phis.size(); ++j) {
      const double r = (1 - w) * a[j] + w * b[j];
      loop.push_back({r * std::cos(phis[j]), -r * std::sin(phis[j])});
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// The fold-frame loops of fold `fold` of a 'within' surface at each of the n + 1 heights, m
/// points each, and which of them are blends. With one `section`: its loop (fold 0's or the
/// fold's own) resampled by arc length, at every height. With `sections`: each section's loop
/// resampled by arc length from its largest u and normalised to u in 0..1 (w by the same
/// factor), blended point by point between the two sections around the height i / n (the
/// rails' normalised arc length, as within_heights spaces them) by a smoothstep.
std::pair<std::vector<Polyline2>, std::vector<bool>> within_fold_loops(
    const SurfaceSpec& spec, const std::vector<std::vector<Polyline2>>& frame_loops, int n, int m,
    int fold) {
  auto loop_of = [&](size_t sec) {
    const std::vector<Polyline2>& loops = frame_loops[sec];
    return resample_uniform(loops[loops.size() == 1 ? 0 : static_cast<size_t>(fold)], true, m);
  };
  const size_t rows = static_cast<size_t>(n) + 1;
  if (spec.sections.empty())
    return {std::vector<Polyline2>(rows, loop_of(0)), std::vector<bool>(rows, false)};
  std::vector<Polyline2> unit;
  for (size_t sec = 0; sec < spec.sections.size(); ++sec) {
    Polyline2 loop = loop_of(sec);
    const auto [umin, umax] = u_range(loop);
    for (auto& p : loop) p = {(p.x - umin) / (umax - umin), p.y / (umax - umin)};
    unit.push_back(std::move(loop));
  }
  std::vector<Polyline2> out;
  std::vector<bool> blended;
  for (size_t i = 0; i < rows; ++i) {
    const auto [k, w] = height_blend(spec.sections, static_cast<double>(i) / n);
    const Polyline2& a = unit[k];
    const Polyline2& b = unit[std::min(k + 1, unit.size() - 1)];
    Polyline2 loop;
    for (int j = 0; j < m; ++j) loop.push_back((1 - w) * a[j] + w * b[j]);
    out.push_back(std::move(loop));
    blended.push_back(w > 0);
  }
  return {out, blended};
}

}  // namespace

DsSurface sweep_around(const SurfaceSpec& spec, const Template& t, size_t max_vertices) {
  CUTAWAY_CHECK(spec.kind == SurfaceKind::Around);
  const double edge = t.edge_m;
  const Polyline2 prof_fit = fit_curve(spec.profile, false, spec.smooth);
  const int n = segments_for(curve_length(prof_fit, false), edge, 2);
  // Every ring has at least 8 vertices: refuse before sampling the profile finely.
  check_vertex_budget(static_cast<size_t>(n) + 1, 8, spec, t, max_vertices);
  const Polyline2 prof = resample_uniform(prof_fit, false, n + 1);
  double max_r = 0;
  for (const auto& p : prof) max_r = std::max(max_r, p.x);

  // The section as a unit-radius-at-angle-0 loop, perimeter in those units.
  double perimeter = 2 * kPi;
  Polyline2 started;
  double rho0 = 1;
  if (!spec.section.circle) {
    started = around_loop_from_angle0(fit_curve(spec.section.loops[0], true, spec.smooth));
    rho0 = glm::length(started.front());
    perimeter = curve_length(started, true) / rho0;
  }
  for (const HeightSection& h : spec.sections) {  // the longest of the sections at heights
    if (h.section.circle) continue;
    const Polyline2 loop =
        around_loop_from_angle0(fit_curve(h.section.loops[0], true, spec.smooth));
    perimeter = std::max(perimeter, curve_length(loop, true) / glm::length(loop.front()));
  }
  const bool partial = spec.span_rad.y > spec.span_rad.x;
  const double turn = partial ? spec.span_rad.y - spec.span_rad.x : 2 * kPi;
  int m = segments_for(max_r * perimeter * turn / (2 * kPi), edge, partial ? 4 : 8);
  // An N-fold object maps onto itself under a turn by 2 pi / N only if every fold gets the same
  // samples: a multiple of N, so that sample k m / N lies where sample 0 turned by k folds lies.
  if (!partial && t.symmetry == Symmetry::NFold && t.folds > 1)
    m = (m + t.folds - 1) / t.folds * t.folds;
  check_vertex_budget(static_cast<size_t>(n) + 1, static_cast<size_t>(m) + partial, spec, t,
                      max_vertices);
  // Equal angles where the section changes with height or the surface covers a span (a ring
  // per profile sample); equal arc length otherwise (a single section all the way round, one
  // ring for every height).
  Polyline2 unit_loop;
  std::vector<Polyline2> at_height;
  if (partial || !spec.sections.empty()) {
    std::vector<double> phis;
    for (int j = 0; j < m + partial; ++j) phis.push_back(spec.span_rad.x + turn * j / m);
    at_height = unit_rings_at_angles(spec, n, phis);
  } else if (spec.section.circle) {
    for (int j = 0; j < m; ++j) {
      const double phi = 2 * kPi * j / m;
      unit_loop.push_back({std::cos(phi), -std::sin(phi)});
    }
  } else {
    for (const auto& p : resample_uniform(started, true, m)) unit_loop.push_back(p / rho0);
  }
  SweepGrid g;
  g.open_rows = partial;
  const int cols = m + partial;
  for (int i = 0; i <= n; ++i) {
    const double r = prof[i].x, y = prof[i].y, tp = static_cast<double>(i) / n;
    const Polyline2& unit = at_height.empty() ? unit_loop : at_height[static_cast<size_t>(i)];
    std::vector<glm::dvec3> row;
    std::vector<glm::dvec2> par;
    if ((i == 0 || i == n) && r <= 0) {
      row.push_back({0, y, 0});
      par.push_back({tp, 0});
    } else {
      for (int j = 0; j < cols; ++j) {
        row.push_back({r * unit[j].x, y, r * unit[j].y});
        par.push_back({tp, static_cast<double>(j) / m});
      }
    }
    g.rows.push_back(std::move(row));
    g.params.push_back(std::move(par));
  }
  DsSurface s;
  s.name = spec.name;
  s.role = spec.is_skin ? SurfaceRole::Skin : SurfaceRole::Structure;
  s.visible_front = spec.visible_front;
  s.visible_back = spec.visible_back;
  s.rigid = spec.rigid;
  add_grid(g, spec, t.ripeness, false, s.mesh);
  return s;
}

DsSurface sweep_within(const SurfaceSpec& spec, const Template& t, size_t max_vertices) {
  CUTAWAY_CHECK(spec.kind == SurfaceKind::Within);
  CUTAWAY_CHECK(t.symmetry == Symmetry::NFold);
  const double edge = t.edge_m;
  const WithinRails rails = within_rails(spec);

  // Heights spaced by the mean normalised arc length of both rails.
  const int n = segments_for(rails.mean_length, edge, 2);
  // Every ring has at least 8 vertices: refuse before placing the heights.
  check_vertex_budget(static_cast<size_t>(n + 1) * t.folds, 8, spec, t, max_vertices);
  const std::vector<double> heights = within_heights(rails, n);

  // The section loops in their fold frames (per section at a height, per loop); the points per
  // ring from the longest loop once stretched to the widest span between the rails.
  std::vector<std::vector<Polyline2>> frame_loops;
  double max_width = 0;
  for (int i = 0; i <= n; ++i)
    max_width = std::max(max_width, rails.outer.at(rails.outer.r, heights[i]) -
                                        rails.inner.at(rails.inner.r, heights[i]));
  double max_scaled_perimeter = 0;
  for (const SectionSpec* section : sections_of(spec)) {
    std::vector<Polyline2> loops;
    for (size_t k = 0; k < section->loops.size(); ++k) {
      Polyline2 uw = fold_frame_loop(*section, spec.smooth, t, k);
      const auto [umin, umax] = u_range(uw);
      max_scaled_perimeter =
          std::max(max_scaled_perimeter, curve_length(uw, true) * max_width / (umax - umin));
      loops.push_back(std::move(uw));
    }
    frame_loops.push_back(std::move(loops));
  }
  const int m = segments_for(max_scaled_perimeter, edge, 8);
  check_vertex_budget(static_cast<size_t>(n + 1) * t.folds, static_cast<size_t>(m), spec, t,
                      max_vertices);

  DsSurface s;
  s.name = spec.name;
  s.role = spec.is_skin ? SurfaceRole::Skin : SurfaceRole::Structure;
  s.visible_front = spec.visible_front;
  s.visible_back = spec.visible_back;
  s.rigid = spec.rigid;
  for (int fold = 0; fold < t.folds; ++fold) {
    const auto [loops, blended] = within_fold_loops(spec, frame_loops, n, m, fold);
    const SweepGrid g = within_fold_grid(spec, t, rails, heights, loops, blended, fold);
    add_grid(g, spec, t.ripeness, grid_volume(g) < 0, s.mesh);
  }
  return s;
}

}  // namespace cutaway
