#include "section/band_sampling.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/error.h"

namespace cutaway {

namespace {

/// Cosine of the largest angle between two lines that run alongside each other (25 degrees).
constexpr double kAlongside = 0.9;

/// Indices of `points` by line, then arc length (then index: deterministic for equal arc
/// lengths).
std::vector<size_t> points_along_lines(std::span<const BandPoint> points) {
  std::vector<size_t> order(points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::tie(points[a].line, points[a].arc_length, a) <
           std::tie(points[b].line, points[b].arc_length, b);
  });
  return order;
}

}  // namespace

SegmentChains chain_segments(std::span<const std::array<glm::dvec2, 2>> segments,
                             std::span<const int> group) {
  const size_t n = segments.size();
  if (group.size() != n) throw InternalError("chain_segments: one group per segment");
  SegmentChains out;
  out.chain.assign(n, -1);
  out.offset.assign(n, 0.0);
  out.forward.assign(n, true);
  // (group, end point) -> the segments of the group that end there.
  std::map<std::tuple<int, double, double>, std::vector<size_t>> ends;
  for (size_t i = 0; i < n; ++i) {
    if (group[i] < 0) continue;
    for (const glm::dvec2& p : segments[i]) ends[{group[i], p.x, p.y}].push_back(i);
  }
  // The other segment of the group joined to segment i at end point p, or n.
  auto joined = [&](size_t i, const glm::dvec2& p) {
    const std::vector<size_t>& at = ends.at({group[i], p.x, p.y});
    if (at.size() != 2) return n;
    return at[0] == i ? at[1] : at[0];
  };
  for (size_t first = 0; first < n; ++first) {
    if (group[first] < 0 || out.chain[first] >= 0) continue;
    // Walk back from `first` to the chain's start (or once round a closed loop).
    size_t start = first;
    glm::dvec2 entry = segments[first][0];  // where the chain enters `start`
    for (size_t steps = 0; steps < n; ++steps) {
      const size_t prev = joined(start, entry);
      if (prev == n || prev == first || out.chain[prev] >= 0) break;
      entry = segments[prev][0] == entry ? segments[prev][1] : segments[prev][0];
      start = prev;
    }
    // Walk forward, laying out arc lengths.
    const int id = out.chains++;
    double s = 0;
    size_t i = start;
    while (i < n && out.chain[i] < 0) {
      out.chain[i] = id;
      out.offset[i] = s;
      out.forward[i] = segments[i][0] == entry;
      const glm::dvec2 exit = out.forward[i] ? segments[i][1] : segments[i][0];
      s += glm::distance(segments[i][0], segments[i][1]);
      entry = exit;
      i = joined(i, exit);
    }
    out.length.push_back(s);
    out.closed.push_back(i == start);
  }
  return out;
}

void mark_irregular_band_points(std::span<BandPoint> points, const SegmentChains& chains) {
  // Points in a uniform grid of cells as wide as the widest band.
  double cell = 0;
  for (const BandPoint& p : points) cell = std::max(cell, p.width);
  if (!(cell > 0)) return;
  auto key = [&](const glm::dvec3& p) {
    return std::make_tuple(static_cast<long>(std::floor(p.x / cell)),
                           static_cast<long>(std::floor(p.y / cell)),
                           static_cast<long>(std::floor(p.z / cell)));
  };
  std::map<std::tuple<long, long, long>, std::vector<size_t>> grid;
  for (size_t i = 0; i < points.size(); ++i) grid[key(points[i].position)].push_back(i);
  auto near_open_end = [&](const BandPoint& p) {
    const int chain = p.line / 3;
    if (chain < 0 || chain >= chains.chains)
      throw InternalError("mark_irregular_band_points: a line of no chain");
    return !chains.closed[chain] &&
           std::min(p.arc_length, chains.length[chain] - p.arc_length) < 2 * p.width;
  };
  // Each point's direction along its line, from its neighbours on the line (0: a line of one
  // point).
  const std::vector<size_t> order = points_along_lines(points);
  std::vector<glm::dvec3> along(points.size(), glm::dvec3(0.0));
  for (size_t k = 0; k < order.size(); ++k) {
    auto on_line = [&](size_t j) { return points[order[j]].line == points[order[k]].line; };
    const size_t before = k > 0 && on_line(k - 1) ? order[k - 1] : order[k];
    const size_t after = k + 1 < order.size() && on_line(k + 1) ? order[k + 1] : order[k];
    const glm::dvec3 d = points[after].position - points[before].position;
    if (glm::length(d) > 0) along[order[k]] = glm::normalize(d);
  }
  for (size_t i = 0; i < points.size(); ++i) {
    BandPoint& p = points[i];
    if (near_open_end(p)) {
      p.exact = true;
      continue;
    }
    const auto [x, y, z] = key(p.position);
    for (long dx = -1; dx <= 1 && !p.exact; ++dx)
      for (long dy = -1; dy <= 1 && !p.exact; ++dy)
        for (long dz = -1; dz <= 1 && !p.exact; ++dz) {
          const auto found = grid.find({x + dx, y + dy, z + dz});
          if (found == grid.end()) continue;
          for (size_t j : found->second) {
            const BandPoint& q = points[j];
            const double d = glm::distance(p.position, q.position);
            if (d >= 0.9 * p.width || j == i) continue;
            // Another band running alongside, at least half a width away: a strip beside a
            // strip (a sheet just under the skin), still interpolable along the line.
            if (q.line / 3 != p.line / 3 && d >= 0.5 * p.width && !near_open_end(q) &&
                std::fabs(glm::dot(along[i], along[j])) > kAlongside)
              continue;
            if (q.line != p.line || std::fabs(q.arc_length - p.arc_length) > 1.5 * d + p.width) {
              p.exact = true;
              break;
            }
          }
        }
  }
}

BandSamplingCounts sample_bands(std::span<const BandPoint> points,
                                const DiffusionBackend& diffusion,
                                const BandSamplingOptions& options, std::span<glm::dvec3> colour,
                                std::span<glm::dvec2> material) {
  check_channel_sizes(points.size(), colour.size(), material.size());
  if (material.size() != points.size())
    throw InternalError("sample_bands: one material entry per point");
  if (!(options.spacing_m > 0)) throw InternalError("sample_bands: spacing must be > 0");
  BandSamplingCounts counts;
  counts.points = points.size();
  const std::vector<size_t> order = points_along_lines(points);
  std::vector<bool> sampled(points.size(), false);
  auto diffuse = [&](const std::vector<size_t>& which) {
    std::vector<glm::dvec3> where;
    for (size_t i : which) where.push_back(points[i].position);
    diffusion.diffuse_into(where, which, colour, material);
    for (size_t i : which) sampled[i] = true;
    counts.diffused += which.size();
  };
  // First samples: each line's ends and points at most spacing_m apart.
  std::vector<size_t> first;
  double last = 0;  // arc length of the line's latest first sample
  for (size_t k = 0; k < order.size(); ++k) {
    const BandPoint& p = points[order[k]];
    const bool line_start = k == 0 || points[order[k - 1]].line != p.line;
    const bool line_end = k + 1 == order.size() || points[order[k + 1]].line != p.line;
    if (line_start || line_end || p.exact ||
        points[order[k + 1]].arc_length - last > options.spacing_m) {
      first.push_back(order[k]);
      last = p.arc_length;
    }
  }
  diffuse(first);
  // Gaps between consecutive samples of a line with points in them (positions in `order`).
  std::vector<std::pair<size_t, size_t>> gaps;
  auto collect_gaps = [&] {
    gaps.clear();
    size_t prev = order.size();
    for (size_t k = 0; k < order.size(); ++k) {
      if (!sampled[order[k]]) continue;
      if (prev < order.size() && points[order[prev]].line == points[order[k]].line && k > prev + 1)
        gaps.emplace_back(prev, k);
      prev = k;
    }
  };
  collect_gaps();
  while (!gaps.empty()) {
    // The point nearest each gap's middle.
    std::vector<size_t> tests, middle;
    for (const auto& [lo, hi] : gaps) {
      const double mid = 0.5 * (points[order[lo]].arc_length + points[order[hi]].arc_length);
      size_t best = lo + 1;
      for (size_t k = lo + 2; k < hi; ++k)
        if (std::fabs(points[order[k]].arc_length - mid) <
            std::fabs(points[order[best]].arc_length - mid))
          best = k;
      middle.push_back(best);
      tests.push_back(order[best]);
    }
    // Interpolations to judge them by, before they become samples.
    std::vector<glm::dvec3> c_interp;
    std::vector<glm::dvec2> m_interp;
    for (size_t g = 0; g < gaps.size(); ++g) {
      const size_t a = order[gaps[g].first], b = order[gaps[g].second], t = tests[g];
      const double span = points[b].arc_length - points[a].arc_length;
      const double w = span > 0 ? (points[t].arc_length - points[a].arc_length) / span : 0.5;
      c_interp.push_back(glm::mix(colour[a], colour[b], w));
      m_interp.push_back(glm::mix(material[a], material[b], w));
    }
    diffuse(tests);
    std::vector<std::pair<size_t, size_t>> next;
    for (size_t g = 0; g < gaps.size(); ++g) {
      const size_t t = tests[g];
      if (options.tolerance.accepts(colour[t], material[t], c_interp[g], m_interp[g])) continue;
      ++counts.failed;
      const auto [lo, hi] = gaps[g];
      if (middle[g] > lo + 1) next.emplace_back(lo, middle[g]);
      if (hi > middle[g] + 1) next.emplace_back(middle[g], hi);
    }
    gaps = std::move(next);
  }
  // Every other point: linear interpolation between the samples around it.
  collect_gaps();
  for (const auto& [lo, hi] : gaps) {
    const size_t a = order[lo], b = order[hi];
    const double span = points[b].arc_length - points[a].arc_length;
    for (size_t k = lo + 1; k < hi; ++k) {
      const size_t i = order[k];
      const double w = span > 0 ? (points[i].arc_length - points[a].arc_length) / span : 0.5;
      colour[i] = glm::mix(colour[a], colour[b], w);
      material[i] = glm::mix(material[a], material[b], w);
    }
  }
  return counts;
}

}  // namespace cutaway
