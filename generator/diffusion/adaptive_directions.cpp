#include "diffusion/adaptive_directions.h"

#include <algorithm>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "base/error.h"

namespace cutaway {

namespace {

/// Neighbours compared per coarse texel: the 4 sharing an edge (at a cube edge, the nearest
/// texels of the next face instead). A silhouette crossing a texel changes what an edge
/// neighbour sees as well; comparing the 4 corner neighbours too cast 13 % more rays for an
/// error change under 0.02/255 (doc/algorithms.md §2).
constexpr size_t kNeighbours = 4;

}  // namespace

std::array<unsigned, 4> AdaptiveDirections::children(unsigned k) const {
  const unsigned m = static_cast<unsigned>(coarse.n), n = static_cast<unsigned>(fine.n);
  const unsigned face = k / (m * m), row = (k / m) % m, column = k % m;
  const unsigned first = face * n * n + 2 * row * n + 2 * column;
  return {first, first + 1, first + n, first + n + 1};
}

AdaptiveDirections make_adaptive_directions(int n) {
  if (n < 2 || n % 2 != 0)
    throw InternalError("adaptive directions: the cube size must be even and >= 2, got " +
                        std::to_string(n));
  AdaptiveDirections d;
  d.coarse = make_cube_directions(n / 2);
  d.fine = make_cube_directions(n);
  const size_t count = d.coarse.direction.size();
  std::vector<std::pair<float, unsigned>> by_angle;
  for (size_t k = 0; k < count; ++k) {
    by_angle.clear();
    for (size_t j = 0; j < count; ++j)
      if (j != k)
        by_angle.emplace_back(-glm::dot(d.coarse.direction[k], d.coarse.direction[j]),
                              static_cast<unsigned>(j));
    const size_t nearest = std::min(kNeighbours, by_angle.size());
    std::partial_sort(by_angle.begin(), by_angle.begin() + static_cast<long>(nearest),
                      by_angle.end());
    for (size_t i = 0; i < nearest; ++i) {
      const unsigned j = by_angle[i].second;
      d.pairs.emplace_back(std::min<unsigned>(k, j), std::max<unsigned>(k, j));
    }
  }
  auto less = [](const glm::uvec2& a, const glm::uvec2& b) {
    return a.x != b.x ? a.x < b.x : a.y < b.y;
  };
  std::sort(d.pairs.begin(), d.pairs.end(), less);
  d.pairs.erase(std::unique(d.pairs.begin(), d.pairs.end()), d.pairs.end());
  return d;
}

void mark_refined_texels(const AdaptiveDirections& directions, std::span<const int> seen,
                         std::span<unsigned char> refine) {
  CUTAWAY_CHECK_OP(seen.size(), ==, directions.coarse.direction.size());
  CUTAWAY_CHECK_OP(refine.size(), ==, seen.size());
  std::fill(refine.begin(), refine.end(), 0);
  for (const glm::uvec2& p : directions.pairs)
    if (seen[p.x] != seen[p.y]) refine[p.x] = refine[p.y] = 1;
}

}  // namespace cutaway
