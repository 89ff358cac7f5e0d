// Improved Perlin noise in 3D (Perlin 2002, "Improving noise", SIGGRAPH 2002): gradient noise on
// the integer lattice with the quintic fade 6t^5 - 15t^4 + 10t^3 and the 12 cube-edge gradients,
// for the NPR colour modulation of doc/algorithms.md §6 (paper §5, Fig. 10).
#pragma once

#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

namespace cutaway {

/// One instance of improved Perlin noise. The 256-entry permutation table is a Fisher-Yates
/// shuffle drawn from Rng(seed) (generator/base/random.h), so every seed, e.g. every object
/// variant, gets its own noise; the same seed gives the same values on every platform.
///
/// Properties (tests/generator/material/perlin_noise_test.cpp checks them):
/// - 0 at every integer lattice point;
/// - C2-continuous (the quintic fade makes the second derivative continuous across cells);
/// - |value| <= kBound for every point and every seed: kBound is the maximum over the unit
///   cell of sum_corners fade_weight * max_gradient (gradient . offset), about 1.0364; typical
///   values are smaller (standard deviation about 0.27 over random points);
/// - mean about 0 over large regions (the gradient set is symmetric);
/// - periodic with period 256 along each axis (the table wraps).
class PerlinNoise {
 public:
  /// An upper bound of |operator()(p)| for every p and every seed (see above).
  static constexpr double kBound = 1.0364;

  /// @param seed usually derive_seed(...) of the caller's path (object, purpose)
  explicit PerlinNoise(uint64_t seed);

  /// The noise at `p`, in lattice units (one unit = one lattice cell).
  /// @pre p finite (a broken invariant otherwise: CUTAWAY_CHECK)
  double operator()(const glm::dvec3& p) const;

  /// The noise at `p` with the lattice wrapped every `period_x` cells along x: a function of
  /// p.x modulo period_x, continuous across the wrap (C2 like everywhere else). An angle mapped
  /// to x = angle / 2 pi * period_x so gives noise round a circle without a seam. With
  /// period_x = 256 it equals operator()(p).
  /// @pre p finite; 1 <= period_x <= 256 (a broken invariant otherwise: CUTAWAY_CHECK)
  double periodic(const glm::dvec3& p, unsigned period_x) const;

  /// The permutation of 0..255 the lattice hashes with (for tests).
  const std::array<uint8_t, 256>& permutation() const { return perm_; }

 private:
  std::array<uint8_t, 256> perm_{};
};

}  // namespace cutaway
