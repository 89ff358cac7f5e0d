#include "section/split_lines.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace cutaway {

std::vector<Line2> split_lines(const Plane& plane, const glm::dvec3& u, const glm::dvec3& v,
                               const std::vector<Plane>& others) {
  std::vector<Line2> out;
  for (const Plane& q : others) {
    glm::dvec2 n(glm::dot(u, q.normal), glm::dot(v, q.normal));
    const double len = glm::length(n);
    if (len < 1e-9) continue;  // parallel planes never meet
    double c = glm::dot(q.point - plane.point, q.normal) / len;
    n /= len;
    if (n.x < 0 || (n.x == 0 && n.y < 0)) {
      n = -n;
      c = -c;
    }
    bool seen = false;
    for (const Line2& l : out)
      seen = seen || (glm::length(l.normal - n) < 1e-12 && std::fabs(l.offset - c) < 1e-12);
    if (!seen) out.push_back({n, c});
  }
  return out;
}

std::vector<Constraint2> arrange_split_lines(
    const std::vector<std::pair<glm::dvec2, glm::dvec2>>& segments, const std::vector<Line2>& lines,
    const glm::dvec2& lo, const glm::dvec2& hi, double snap_m) {
  // Points along each segment (parameter 0..1) and along each line (distance from its foot).
  std::vector<std::vector<std::pair<double, glm::dvec2>>> on_segment(segments.size());
  std::vector<std::vector<std::pair<double, glm::dvec2>>> on_line(lines.size());
  std::vector<bool> line_used(lines.size(), false);
  std::vector<double> t_lo(lines.size()), t_hi(lines.size());
  auto foot = [](const Line2& l) { return l.normal * l.offset; };
  auto dir = [](const Line2& l) { return glm::dvec2(-l.normal.y, l.normal.x); };

  // Each line clipped to the box (Liang-Barsky).
  for (size_t j = 0; j < lines.size(); ++j) {
    const glm::dvec2 p0 = foot(lines[j]), d = dir(lines[j]);
    double t0 = -1e300, t1 = 1e300;
    bool inside = true;
    for (int k = 0; k < 2; ++k) {
      if (std::fabs(d[k]) < 1e-15) {
        inside = inside && p0[k] >= lo[k] && p0[k] <= hi[k];
        continue;
      }
      double ta = (lo[k] - p0[k]) / d[k], tb = (hi[k] - p0[k]) / d[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (!inside || t0 >= t1) continue;
    line_used[j] = true;
    t_lo[j] = t0;
    t_hi[j] = t1;
    on_line[j].push_back({t0, p0 + d * t0});
    on_line[j].push_back({t1, p0 + d * t1});
  }
  // Segment-line crossings. An end point within snap_m of a line lies on it (the line bends
  // through it): no crossing is made a hair's breadth from a cut vertex.
  for (size_t i = 0; i < segments.size(); ++i) {
    const auto& [a, b] = segments[i];
    for (size_t j = 0; j < lines.size(); ++j) {
      if (!line_used[j]) continue;
      auto side = [&](const glm::dvec2& p) {
        const double d = glm::dot(p, lines[j].normal) - lines[j].offset;
        return std::fabs(d) <= snap_m ? 0.0 : d;
      };
      const double da = side(a), db = side(b);
      auto on_line_at = [&](const glm::dvec2& p) {
        on_line[j].push_back({glm::dot(p - foot(lines[j]), dir(lines[j])), p});
      };
      if (da == 0 || db == 0) {  // the line passes through an end point (or both)
        if (da == 0) on_line_at(a);
        if (db == 0) on_line_at(b);
        continue;
      }
      if ((da > 0) == (db > 0)) continue;
      const double t = da / (da - db);
      const glm::dvec2 p = a + (b - a) * t;
      on_segment[i].push_back({t, p});
      on_line_at(p);
    }
  }
  // Line-line crossings inside the box.
  for (size_t j = 0; j < lines.size(); ++j) {
    for (size_t k = j + 1; k < lines.size(); ++k) {
      if (!line_used[j] || !line_used[k]) continue;
      const glm::dvec2 n1 = lines[j].normal, n2 = lines[k].normal;
      const double det = n1.x * n2.y - n1.y * n2.x;
      if (std::fabs(det) < 1e-12) continue;
      const glm::dvec2 p((lines[j].offset * n2.y - lines[k].offset * n1.y) / det,
                         (n1.x * lines[k].offset - n2.x * lines[j].offset) / det);
      const double tj = glm::dot(p - foot(lines[j]), dir(lines[j]));
      const double tk = glm::dot(p - foot(lines[k]), dir(lines[k]));
      if (tj <= t_lo[j] || tj >= t_hi[j] || tk <= t_lo[k] || tk >= t_hi[k]) continue;
      on_line[j].push_back({tj, p});
      on_line[k].push_back({tk, p});
    }
  }

  std::vector<Constraint2> out;
  auto emit = [&out](std::vector<std::pair<double, glm::dvec2>>& points, int segment) {
    std::sort(points.begin(), points.end(), [](const auto& x, const auto& y) {
      return x.first != y.first
                 ? x.first < y.first
                 : std::tie(x.second.x, x.second.y) < std::tie(y.second.x, y.second.y);
    });
    for (size_t k = 0; k + 1 < points.size(); ++k)
      if (points[k].second != points[k + 1].second)
        out.push_back({points[k].second, points[k + 1].second, segment});
  };
  for (size_t i = 0; i < segments.size(); ++i) {
    on_segment[i].push_back({0.0, segments[i].first});
    on_segment[i].push_back({1.0, segments[i].second});
    emit(on_segment[i], static_cast<int>(i));
  }
  for (size_t j = 0; j < lines.size(); ++j)
    if (line_used[j]) emit(on_line[j], -1);
  return out;
}

}  // namespace cutaway
