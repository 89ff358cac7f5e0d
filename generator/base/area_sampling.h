// Area-uniform random points on triangles: a triangle with probability proportional to its
// area, then uniform barycentric weights (the unit square folded onto the triangle). Grain
// placement (variation/grains.cpp) draws its candidate centres this way.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "base/random.h"

namespace cutaway {

/// A point drawn by AreaSampler.
struct AreaSample {
  size_t triangle = 0;          ///< index into the areas given to AreaSampler
  glm::dvec3 weights{1, 0, 0};  ///< barycentric weights of the triangle's corners 0, 1, 2
};

/// Draws points uniformly by area over a list of triangles.
/// Source: Turk 1990, "Generating random points in triangles" (Graphics Gems), the fold.
class AreaSampler {
 public:
  /// @param areas #T triangle areas (any unit, each >= 0), summed in order; a triangle of area
  /// 0 is never drawn
  explicit AreaSampler(const std::vector<double>& areas);

  /// The sum of the areas.
  double total() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }

  /// Draws a point with three draws of `rng`: rng.uniform(0, total()) picks the triangle, two
  /// rng.uniform() its weights. Deterministic for a given rng state.
  /// @pre total() > 0
  AreaSample draw(Rng& rng) const;

 private:
  std::vector<double> cumulative_;  ///< running sum of the areas
};

}  // namespace cutaway
