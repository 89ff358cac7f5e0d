#include "pieces/manifold_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>

#include <glm/geometric.hpp>

namespace cutaway {

namespace {

/// Fails at the first pair of distinct positions closer than `d` (uniform grid of cell d).
/// Cells are visited in lexicographic order and the points of a cell in their order in `points`.
Check near_duplicates(const std::vector<glm::dvec3>& points, double d) {
  using Cell = std::array<int64_t, 3>;
  auto cell_of = [d](const glm::dvec3& p) {
    return Cell{static_cast<int64_t>(std::floor(p.x / d)),
                static_cast<int64_t>(std::floor(p.y / d)),
                static_cast<int64_t>(std::floor(p.z / d))};
  };
  std::vector<std::pair<Cell, unsigned>> grid(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    grid[i] = {cell_of(points[i]), static_cast<unsigned>(i)};
  std::sort(grid.begin(), grid.end());
  auto cell_less = [](const std::pair<Cell, unsigned>& a, const Cell& c) { return a.first < c; };
  for (size_t begin = 0, end = 0; begin < grid.size(); begin = end) {
    const Cell c = grid[begin].first;
    while (end < grid.size() && grid[end].first == c) ++end;
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const Cell n{c[0] + dx, c[1] + dy, c[2] + dz};
          auto it = std::lower_bound(grid.begin(), grid.end(), n, cell_less);
          for (size_t i = begin; i < end; ++i)
            for (auto q = it; q != grid.end() && q->first == n; ++q) {
              const glm::dvec3& p = points[grid[i].second];
              const glm::dvec3& r = points[q->second];
              if (p != r && glm::distance(p, r) < d)
                return Check::none("two vertices " + std::to_string(glm::distance(p, r)) +
                                   " m apart");
            }
        }
  }
  return {};
}

/// Welds the corners of `mesh` by exact position: #F welded triangles, and in `welded` the
/// distinct positions in the order of their first corner.
std::vector<std::array<unsigned, 3>> weld(const ShadedMesh& mesh, std::vector<glm::dvec3>& welded) {
  const size_t corners = 3 * mesh.triangle.size();
  auto at = [&mesh](size_t c) -> const glm::dvec3& {
    return mesh.position[mesh.triangle[c / 3][static_cast<int>(c % 3)]];
  };
  // Corners sorted by position, ties by corner: each run of equal positions starts with the
  // position's first corner.
  struct Corner {
    double x, y, z;
    size_t corner;
    bool operator<(const Corner& o) const {
      return std::tie(x, y, z, corner) < std::tie(o.x, o.y, o.z, o.corner);
    }
    bool same_place(const Corner& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  std::vector<Corner> order(corners);
  for (size_t c = 0; c < corners; ++c) order[c] = {at(c).x, at(c).y, at(c).z, c};
  std::sort(order.begin(), order.end());
  std::vector<size_t> first(corners);  // corner -> the first corner at its position
  for (size_t i = 0; i < corners; ++i)
    first[order[i].corner] =
        i > 0 && order[i - 1].same_place(order[i]) ? first[order[i - 1].corner] : order[i].corner;
  // Ids in the order of the first corners; a corner's first corner comes no later than itself.
  std::vector<unsigned> id(corners, 0);
  std::vector<std::array<unsigned, 3>> tris(mesh.triangle.size());
  welded.clear();
  for (size_t c = 0; c < corners; ++c) {
    if (first[c] == c) {
      id[c] = static_cast<unsigned>(welded.size());
      welded.push_back(at(c));
    }
    tris[c / 3][c % 3] = id[first[c]];
  }
  return tris;
}

}  // namespace

Check check_manifold(const ShadedMesh& mesh, double min_separation_m) {
  std::vector<glm::dvec3> welded;
  const std::vector<std::array<unsigned, 3>> tris = weld(mesh, welded);
  for (const auto& w : tris) {
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0])
      return Check::none("a triangle with two corners at one point");
    if (!(glm::length(glm::cross(welded[w[1]] - welded[w[0]], welded[w[2]] - welded[w[0]])) > 0))
      return Check::none("a triangle of zero area");
  }
  // Directed edges, sorted: each must occur once, and its twin too.
  std::vector<std::pair<unsigned, unsigned>> directed;
  directed.reserve(3 * tris.size());
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) directed.emplace_back(t[k], t[(k + 1) % 3]);
  std::sort(directed.begin(), directed.end());
  for (size_t begin = 0, end = 0; begin < directed.size(); begin = end) {
    while (end < directed.size() && directed[end] == directed[begin]) ++end;
    if (end - begin != 1)
      return Check::none("an edge used " + std::to_string(end - begin) + " times one way");
    const std::pair<unsigned, unsigned> twin{directed[begin].second, directed[begin].first};
    if (!std::binary_search(directed.begin(), directed.end(), twin))
      return Check::none("an open edge");
  }
  // Around each vertex v, triangle (v, a, b) links a to b: one cycle through all of them. Every
  // (v, a) occurs once (directed edge v -> a, checked above).
  std::vector<std::array<unsigned, 3>> fan;  // (v, a, b), sorted
  fan.reserve(3 * tris.size());
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) fan.push_back({t[k], t[(k + 1) % 3], t[(k + 2) % 3]});
  std::sort(fan.begin(), fan.end());
  for (size_t begin = 0, end = 0; begin < fan.size(); begin = end) {
    while (end < fan.size() && fan[end][0] == fan[begin][0]) ++end;
    const auto first = fan.begin() + static_cast<long>(begin);
    const auto last = fan.begin() + static_cast<long>(end);
    const size_t links = end - begin;
    size_t steps = 0;
    bool broken = false;  // a link to no link of v (not after the twin check above)
    const unsigned start = fan[begin][1];
    unsigned a = start;
    do {
      const auto it =
          std::lower_bound(first, last, a, [](const std::array<unsigned, 3>& f, unsigned key) {
            return f[1] < key;
          });
      broken = it == last || (*it)[1] != a;
      if (broken) break;
      a = (*it)[2];
    } while (++steps <= links && a != start);
    if (broken || steps != links)
      return Check::none("a vertex with more than one fan of triangles");
  }
  return min_separation_m > 0 ? near_duplicates(welded, min_separation_m) : Check{};
}

}  // namespace cutaway
