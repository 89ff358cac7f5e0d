#include "material/texture_field.h"

#include <cmath>

#include "base/constants.h"
#include "base/error.h"

namespace cutaway {

LatticePoint band_lattice_point(const TextureBand& band, const glm::dvec3& p_m) {
  const double f = band.frequency_per_m;
  switch (band.along) {
    case TextureField::None: return {p_m * f, 0};
    case TextureField::Axial:
      return {glm::dvec3(p_m.x * f, p_m.y * f / band.stretch, p_m.z * f), 0};
    case TextureField::Radial:
    case TextureField::Around: {
      CUTAWAY_CHECK(band.around_cells >= 1 && band.around_cells <= 256);
      const double r = std::sqrt(p_m.x * p_m.x + p_m.z * p_m.z);
      const double theta = std::atan2(p_m.z, p_m.x);
      const double around = theta / (2 * kPi) * band.around_cells;
      const double radial = band.along == TextureField::Radial ? r * f / band.stretch : r * f;
      return {glm::dvec3(around, p_m.y * f, radial), band.around_cells};
    }
  }
  throw InternalError("band_lattice_point: unknown field");
}

}  // namespace cutaway
