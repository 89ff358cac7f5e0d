// Silhouette-adaptive directions for PMVC (doc/algorithms.md §2, Adaptive directions): a point's
// cube map is cast at half its resolution first, and only the coarse texels where the sheet
// seen changes between neighbours (silhouettes, sheet edges, front and back) are cast again at
// full resolution. Elsewhere the integrand (colour / distance) is smooth and one ray per coarse
// texel integrates it as well as four.
#pragma once

#include <array>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "diffusion/cube_directions.h"

namespace cutaway {

/// The two levels of an n x n cube map (n even) and which coarse texels are compared.
struct AdaptiveDirections {
  CubeDirections coarse;  ///< n/2 x n/2 per face: cast for every point
  CubeDirections fine;    ///< n x n per face: four per coarse texel, cast where it is refined
  /// Pairs (i < j) of neighbouring coarse texels, compared after the coarse rays: each texel
  /// with its 4 nearest other texel centres (by angle: the texels sharing an edge with it,
  /// across a cube edge as well); sorted, no duplicates.
  std::vector<glm::uvec2> pairs;

  /// The fine texels (indices into `fine`) that tile coarse texel `k`: rows 2r, 2r + 1 and
  /// columns 2c, 2c + 1 of its face. Their solid angles sum to the coarse texel's.
  std::array<unsigned, 4> children(unsigned k) const;
};

/// The coarse and fine directions of an n x n cube map and the neighbour pairs.
/// @throws InternalError unless n is even and >= 2
AdaptiveDirections make_adaptive_directions(int n);

/// Marks the coarse texels to cast again at full resolution: both texels of every pair whose
/// `seen` values differ. `seen` (#coarse texels): what the texel's ray hit, one value per sheet
/// and side (e.g. 2 sheet + back), -1 for no hit. `refine` (#coarse texels) is overwritten with
/// 0 or 1. Deterministic; the GPU backend applies the same rule (shaders/pmvc_trace.comp).
void mark_refined_texels(const AdaptiveDirections& directions, std::span<const int> seen,
                         std::span<unsigned char> refine);

}  // namespace cutaway
