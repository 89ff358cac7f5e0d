// Worley's cellular texture basis (Worley 1996, "A Cellular Texture Basis Function", SIGGRAPH
// 96): one feature point placed at random in every unit cell of the integer lattice, and at a
// point the distances F1, F2 to the nearest and second-nearest feature points. Skin speckles and
// nets (skin_pattern.h) and the interior's cells (colour_modulation.h) are built on it.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "base/random.h"

namespace cutaway {

/// Uniform in [0, 1) from the top 53 bits of a SplitMix64 step of `state`.
inline double cell_uniform(uint64_t& state) {
  return static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53;
}

/// Calls visit(point, state) for the feature point of each of the 27 cells around `q` (lattice
/// units): a point placed uniformly in its cell from the cell's hash (its z, y, x offsets drawn in
/// that order) derive_seed(cells, {i, j, k}), and that hash's stream after the three uniforms, for
/// whatever else the cell draws. With period_x > 0 the lattice wraps along x every period_x cells:
/// cell i hashes as i modulo period_x, so the points repeat with that period (an angle mapped to x
/// gives cells round a circle without a seam). period_x = 0: no wrap.
template <class Visit>
void visit_feature_points(uint64_t cells, const glm::dvec3& q, unsigned period_x, Visit visit) {
  const glm::dvec3 base = glm::floor(q);
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const glm::dvec3 cell = base + glm::dvec3(dx, dy, dz);
        double hashed_x = cell.x;
        if (period_x > 0) hashed_x -= period_x * std::floor(cell.x / period_x);
        uint64_t state = derive_seed(cells, {static_cast<uint64_t>(static_cast<int64_t>(hashed_x)),
                                             static_cast<uint64_t>(static_cast<int64_t>(cell.y)),
                                             static_cast<uint64_t>(static_cast<int64_t>(cell.z))});
        // z, y, x: the order the first version's unsequenced arguments took with GCC, kept so
        // that patterns keep their bytes.
        const double jz = cell_uniform(state), jy = cell_uniform(state), jx = cell_uniform(state);
        visit(cell + glm::dvec3(jx, jy, jz), state);
      }
}

/// The distances from a point to its nearest and second-nearest feature points.
struct CellDistances {
  double f1 = 0.0;  ///< nearest, lattice units
  double f2 = 0.0;  ///< second nearest, >= f1; f2 - f1 is 0 on a wall between two cells
};

/// F1 and F2 at `q` (lattice units) over the feature points of the 27 cells around it (exact
/// for F1; for F2 exact except in rare configurations where a point two cells away is nearer,
/// which Worley's method accepts).
/// @param cells    the lattice's seed (e.g. derive_seed of the object and the layer)
/// @param q        finite, lattice units
/// @param period_x 0 or the wrap along x, as visit_feature_points
CellDistances cell_distances(uint64_t cells, const glm::dvec3& q, unsigned period_x);

}  // namespace cutaway
