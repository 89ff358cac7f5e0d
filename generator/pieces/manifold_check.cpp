#include "pieces/manifold_check.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>

namespace cutaway {

namespace {

/// The first pair of distinct positions closer than `d` (uniform grid of cell d), as a message.
std::string near_duplicates(const std::vector<glm::dvec3>& points, double d) {
  using Cell = std::tuple<int64_t, int64_t, int64_t>;
  std::map<Cell, std::vector<glm::dvec3>> grid;
  auto cell_of = [d](const glm::dvec3& p) {
    return Cell{static_cast<int64_t>(std::floor(p.x / d)),
                static_cast<int64_t>(std::floor(p.y / d)),
                static_cast<int64_t>(std::floor(p.z / d))};
  };
  for (const glm::dvec3& p : points) grid[cell_of(p)].push_back(p);
  for (const auto& [c, here] : grid)
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const auto it =
              grid.find({std::get<0>(c) + dx, std::get<1>(c) + dy, std::get<2>(c) + dz});
          if (it == grid.end()) continue;
          for (const glm::dvec3& p : here)
            for (const glm::dvec3& q : it->second)
              if (p != q && glm::distance(p, q) < d)
                return "two vertices " + std::to_string(glm::distance(p, q)) + " m apart";
        }
  return "";
}

}  // namespace

std::string manifold_defect(const ShadedMesh& mesh, double min_separation_m) {
  std::map<std::tuple<double, double, double>, unsigned> id;
  std::vector<glm::dvec3> welded;
  std::vector<std::array<unsigned, 3>> tris;
  tris.reserve(mesh.triangle.size());
  for (const glm::uvec3& t : mesh.triangle) {
    std::array<unsigned, 3> w{};
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3& p = mesh.position[t[k]];
      const auto [it, added] =
          id.emplace(std::make_tuple(p.x, p.y, p.z), static_cast<unsigned>(welded.size()));
      if (added) welded.push_back(p);
      w[k] = it->second;
    }
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0])
      return "a triangle with two corners at one point";
    if (!(glm::length(glm::cross(welded[w[1]] - welded[w[0]], welded[w[2]] - welded[w[0]])) > 0))
      return "a triangle of zero area";
    tris.push_back(w);
  }
  std::map<std::pair<unsigned, unsigned>, int> directed;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    if (n != 1) return "an edge used " + std::to_string(n) + " times one way";
    if (!directed.count({e.second, e.first})) return "an open edge";
  }
  // Around each vertex v, triangle (v, a, b) links a to b: one cycle through all of them.
  std::vector<std::map<unsigned, unsigned>> fan(welded.size());
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) fan[t[k]][t[(k + 1) % 3]] = t[(k + 2) % 3];
  for (const auto& next : fan) {
    if (next.empty()) continue;
    size_t steps = 0;
    const unsigned start = next.begin()->first;
    unsigned a = start;
    do {
      a = next.at(a);
    } while (++steps <= next.size() && a != start);
    if (steps != next.size()) return "a vertex with more than one fan of triangles";
  }
  return min_separation_m > 0 ? near_duplicates(welded, min_separation_m) : "";
}

}  // namespace cutaway
