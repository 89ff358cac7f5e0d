#include "model/curves.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "base/error.h"

namespace cutaway {

Polyline2 without_duplicates(const Polyline2& points, bool closed) {
  Polyline2 out;
  for (const auto& p : points) {
    if (out.empty() || glm::distance(out.back(), p) > 1e-12) out.push_back(p);
  }
  if (closed && out.size() > 1 && glm::distance(out.front(), out.back()) <= 1e-12) out.pop_back();
  return out;
}

namespace {

/// One centripetal Catmull-Rom span from p1 to p2 evaluated at u in [0, 1].
glm::dvec2 catmull_rom_span(const glm::dvec2& p0, const glm::dvec2& p1, const glm::dvec2& p2,
                            const glm::dvec2& p3, double u) {
  auto knot = [](const glm::dvec2& a, const glm::dvec2& b) {
    return std::max(std::sqrt(glm::distance(a, b)), 1e-12);
  };
  const double t0 = 0, t1 = t0 + knot(p0, p1), t2 = t1 + knot(p1, p2), t3 = t2 + knot(p2, p3);
  const double t = t1 + u * (t2 - t1);
  const glm::dvec2 a1 = (t1 - t) / (t1 - t0) * p0 + (t - t0) / (t1 - t0) * p1;
  const glm::dvec2 a2 = (t2 - t) / (t2 - t1) * p1 + (t - t1) / (t2 - t1) * p2;
  const glm::dvec2 a3 = (t3 - t) / (t3 - t2) * p2 + (t - t2) / (t3 - t2) * p3;
  const glm::dvec2 b1 = (t2 - t) / (t2 - t0) * a1 + (t - t0) / (t2 - t0) * a2;
  const glm::dvec2 b2 = (t3 - t) / (t3 - t1) * a2 + (t - t1) / (t3 - t1) * a3;
  return (t2 - t) / (t2 - t1) * b1 + (t - t1) / (t2 - t1) * b2;
}

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

/// Orientation of c relative to the line a->b: +1 left, -1 right, 0 collinear (with tolerance).
int orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  const double v = cross(b - a, c - a);
  const double scale = glm::length(b - a) * glm::length(c - a);
  if (std::fabs(v) <= 1e-12 * scale) return 0;
  return v > 0 ? 1 : -1;
}

bool on_segment(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

bool segments_intersect(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                        const glm::dvec2& d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) {
    if (o1 != 0 || o2 != 0) return true;
  }
  if (o1 == 0 && on_segment(a, b, c)) return true;
  if (o2 == 0 && on_segment(a, b, d)) return true;
  if (o3 == 0 && on_segment(c, d, a)) return true;
  if (o4 == 0 && on_segment(c, d, b)) return true;
  return false;
}

}  // namespace

Polyline2 catmull_rom(const Polyline2& input, bool closed, int per_segment) {
  const Polyline2 p = without_duplicates(input, closed);
  CUTAWAY_CHECK_OP(p.size(), >=, 2u);
  const size_t n = p.size();
  auto at = [&](long i) -> glm::dvec2 {
    if (closed)
      return p[static_cast<size_t>(((i % static_cast<long>(n)) + static_cast<long>(n)) %
                                   static_cast<long>(n))];
    if (i < 0) return 2.0 * p[0] - p[1];
    if (i >= static_cast<long>(n)) return 2.0 * p[n - 1] - p[n - 2];
    return p[static_cast<size_t>(i)];
  };
  Polyline2 out;
  const size_t spans = closed ? n : n - 1;
  for (size_t s = 0; s < spans; ++s) {
    const long i = static_cast<long>(s);
    for (int k = 0; k < per_segment; ++k) {
      out.push_back(catmull_rom_span(at(i - 1), at(i), at(i + 1), at(i + 2),
                                     static_cast<double>(k) / per_segment));
    }
  }
  if (!closed) out.push_back(p.back());
  return out;
}

Polyline2 fit_curve(const Polyline2& points, bool closed, bool smooth) {
  if (smooth) return catmull_rom(points, closed);
  const Polyline2 p = without_duplicates(points, closed);
  CUTAWAY_CHECK_OP(p.size(), >=, 2u);
  Polyline2 out;
  const size_t spans = closed ? p.size() : p.size() - 1;
  for (size_t s = 0; s < spans; ++s) {
    const glm::dvec2 a = p[s], b = p[(s + 1) % p.size()];
    for (int k = 0; k < 16; ++k) out.push_back(a + (b - a) * (k / 16.0));
  }
  if (!closed) out.push_back(p.back());
  return out;
}

double curve_length(const Polyline2& c, bool closed) {
  double len = 0;
  for (size_t i = 0; i + 1 < c.size(); ++i) len += glm::distance(c[i], c[i + 1]);
  if (closed && c.size() > 1) len += glm::distance(c.back(), c.front());
  return len;
}

std::vector<double> arc_length_parameters(const Polyline2& c, bool closed) {
  std::vector<double> t(c.size(), 0.0);
  for (size_t i = 1; i < c.size(); ++i) t[i] = t[i - 1] + glm::distance(c[i - 1], c[i]);
  const double total = curve_length(c, closed);
  if (total > 0)
    for (auto& v : t) v /= total;
  return t;
}

Polyline2 resample_uniform(const Polyline2& c, bool closed, int count) {
  CUTAWAY_CHECK(count >= (closed ? 3 : 2));
  CUTAWAY_CHECK(c.size() >= 2);
  Polyline2 pts = c;
  if (closed) pts.push_back(c.front());
  std::vector<double> cum(pts.size(), 0.0);
  for (size_t i = 1; i < pts.size(); ++i) cum[i] = cum[i - 1] + glm::distance(pts[i - 1], pts[i]);
  const double total = cum.back();
  Polyline2 out;
  out.reserve(count);
  const int steps = closed ? count : count - 1;
  size_t seg = 0;
  for (int k = 0; k < count; ++k) {
    const double s = total * k / steps;
    while (seg + 2 < pts.size() && cum[seg + 1] < s) ++seg;
    const double len = cum[seg + 1] - cum[seg];
    const double a = len > 0 ? std::clamp((s - cum[seg]) / len, 0.0, 1.0) : 0.0;
    out.push_back(pts[seg] + (pts[seg + 1] - pts[seg]) * a);
  }
  if (!closed) out.back() = c.back();
  return out;
}

std::optional<std::pair<size_t, size_t>> find_self_intersection(const Polyline2& c, bool closed) {
  const size_t n = c.size();
  if (n < 3) return std::nullopt;
  const size_t segs = closed ? n : n - 1;
  // Sort segments by their lower x bound: a sweep that skips pairs far apart in x.
  std::vector<size_t> order(segs);
  for (size_t i = 0; i < segs; ++i) order[i] = i;
  auto lo = [&](size_t i) { return std::min(c[i].x, c[(i + 1) % n].x); };
  auto hi = [&](size_t i) { return std::max(c[i].x, c[(i + 1) % n].x); };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return lo(a) < lo(b); });
  for (size_t a = 0; a < segs; ++a) {
    const size_t i = order[a];
    for (size_t b = a + 1; b < segs && lo(order[b]) <= hi(i); ++b) {
      const size_t j = order[b];
      const size_t d = i > j ? i - j : j - i;
      if (d == 1 || (closed && d == segs - 1)) continue;  // adjacent segments share a point
      if (segments_intersect(c[i], c[(i + 1) % n], c[j], c[(j + 1) % n])) {
        return std::make_pair(std::min(i, j), std::max(i, j));
      }
    }
  }
  return std::nullopt;
}

double signed_area(const Polyline2& loop) {
  double a = 0;
  for (size_t i = 0; i < loop.size(); ++i) a += cross(loop[i], loop[(i + 1) % loop.size()]);
  return 0.5 * a;
}

int winding_number(const Polyline2& loop, const glm::dvec2& p) {
  int w = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const glm::dvec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    if (a.y <= p.y) {
      if (b.y > p.y && cross(b - a, p - a) > 0) ++w;
    } else if (b.y <= p.y && cross(b - a, p - a) < 0) {
      --w;
    }
  }
  return w;
}

}  // namespace cutaway
