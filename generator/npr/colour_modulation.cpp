#include "npr/colour_modulation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/error.h"
#include "base/random.h"

namespace cutaway {

double band_weight(const PerlinBand& band, const glm::dvec3& colour_linear) {
  if (!band.tinted) return band.amplitude;
  const glm::dvec3 c = linear_to_srgb(glm::clamp(colour_linear, 0.0, 1.0));
  const double d = glm::distance(c, linear_to_srgb(band.tint));
  if (!(d < band.reach)) return 0.0;
  const double q = 1.0 - (d / band.reach) * (d / band.reach);
  return band.amplitude * q * q;
}

ColourModulation::ColourModulation(const NprSettings& npr, uint64_t seed) {
  bands_.reserve(npr.perlin_bands.size());
  for (size_t b = 0; b < npr.perlin_bands.size(); ++b) {
    const uint64_t band_seed = derive_seed(seed, {b});
    Rng rng(derive_seed(band_seed, {1}));  // the offset; the permutation uses band_seed itself
    const glm::dvec3 offset{rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256)};
    bands_.push_back(Band{npr.perlin_bands[b], PerlinNoise(band_seed), offset});
  }
}

double ColourModulation::relative_change(const glm::dvec3& position_m,
                                         const glm::dvec3& colour_linear) const {
  double sum = 0.0;
  for (const Band& b : bands_) {
    const double w = band_weight(b.params, colour_linear);
    if (w == 0.0) continue;
    sum += w * b.noise(position_m * b.params.frequency_per_m + b.offset);
  }
  return sum;
}

glm::dvec3 ColourModulation::operator()(const glm::dvec3& position_m,
                                        const glm::dvec3& colour_linear, double strength) const {
  if (strength == 0.0 || bands_.empty()) return colour_linear;
  const double factor = 1.0 + strength * relative_change(position_m, colour_linear);
  return glm::clamp(colour_linear * factor, 0.0, 1.0);
}

void modulate_colours(std::span<const glm::dvec3> position_m, std::span<glm::dvec3> colour,
                      const NprSettings& npr, double strength, uint64_t seed) {
  if (position_m.size() != colour.size()) {
    throw InternalError("modulate_colours: " + std::to_string(position_m.size()) +
                        " positions but " + std::to_string(colour.size()) + " colours");
  }
  if (!(strength >= 0.0) || !std::isfinite(strength)) {
    throw InternalError("modulate_colours: the strength must be finite and >= 0, not " +
                        std::to_string(strength));
  }
  if (strength == 0.0 || npr.perlin_bands.empty()) return;
  const ColourModulation modulation(npr, seed);
  for (size_t i = 0; i < colour.size(); ++i) {
    colour[i] = modulation(position_m[i], colour[i], strength);
  }
}

void modulate_colours(ShadedMesh& mesh, const NprSettings& npr, double strength, uint64_t seed) {
  modulate_colours(mesh.position, mesh.colour, npr, strength, seed);
}

}  // namespace cutaway
