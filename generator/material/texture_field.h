// Where a point lies on a texture band's lattice when the band is stretched along a direction
// field of the object (doc/algorithms.md §6, Interior texture): the object-frame point mapped to
// cylindrical coordinates about the axis and scaled so that the lattice is `stretch` times
// longer along the field than across it. Noise or cells read at these coordinates are
// anisotropic textures that follow the field (fibres, rays, rings, elongated vesicles) and,
// like everything else in the colour, are functions of the position alone.
#pragma once

#include <glm/vec3.hpp>

#include "model/template.h"

namespace cutaway {

/// A point on a band's lattice.
struct LatticePoint {
  glm::dvec3 q{0.0};      ///< lattice units
  unsigned period_x = 0;  ///< 0, or the period of q.x (the around coordinate) in cells
};

/// The lattice point of the object-frame point `p_m` (metres) for `band`:
/// - None:   q = p f
/// - Axial:  q = (x f, y f / stretch, z f)
/// - Radial: q = (theta / 2 pi * N, y f, r f / stretch), period_x = N
/// - Around: q = (theta / 2 pi * N, y f, r f),           period_x = N
/// with f = band.frequency_per_m, r and theta the distance from the axis and the angle
/// atan2(z, x), N = band.around_cells (which already holds the stretch for Around). Around the
/// axis the lattice spacing is an angle, so features widen with r as real rays and vesicles
/// do; at the axis itself a radial field is singular (all angles meet).
/// @pre p_m finite; band.around_cells in 1..256 for Radial and Around (CUTAWAY_CHECK)
LatticePoint band_lattice_point(const TextureBand& band, const glm::dvec3& p_m);

}  // namespace cutaway
