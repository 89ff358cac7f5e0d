// Finiteness of glm vectors: the guard in front of exports, noise and diffusion.
#pragma once

#include <cmath>

#include <glm/fwd.hpp>

namespace cutaway {

/// Whether every component of `v` is finite (neither NaN nor infinite).
template <glm::length_t N, typename T, glm::qualifier Q>
bool all_finite(const glm::vec<N, T, Q>& v) {
  for (glm::length_t i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

}  // namespace cutaway
