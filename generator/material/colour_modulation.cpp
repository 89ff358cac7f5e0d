#include "material/colour_modulation.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/error.h"
#include "base/random.h"

namespace cutaway {

namespace {

/// The colour clamped to 0..1 and encoded as sRGB, as band_weight compares it.
glm::dvec3 clamped_srgb(const glm::dvec3& colour_linear) {
  return linear_to_srgb(glm::clamp(colour_linear, 0.0, 1.0));
}

/// band_weight of a tinted band, from the colour and the tint already encoded as sRGB.
double tinted_weight(const PerlinBand& band, const glm::dvec3& colour_srgb,
                     const glm::dvec3& tint_srgb) {
  const double d = glm::distance(colour_srgb, tint_srgb);
  if (!(d < band.reach)) return 0.0;
  const double q = 1.0 - (d / band.reach) * (d / band.reach);
  return band.amplitude * q * q;
}

}  // namespace

double band_weight(const PerlinBand& band, const glm::dvec3& colour_linear) {
  if (!band.tinted) return band.amplitude;
  return tinted_weight(band, clamped_srgb(colour_linear), linear_to_srgb(band.tint));
}

ColourModulation::ColourModulation(const NprSettings& npr, uint64_t seed) {
  bands_.reserve(npr.perlin_bands.size());
  for (size_t b = 0; b < npr.perlin_bands.size(); ++b) {
    const uint64_t band_seed = derive_seed(seed, {b});
    Rng rng(derive_seed(band_seed, {1}));  // the offset; the permutation uses band_seed itself
    const glm::dvec3 offset{rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256)};
    bands_.push_back(Band{npr.perlin_bands[b], PerlinNoise(band_seed), offset,
                          linear_to_srgb(npr.perlin_bands[b].tint)});
  }
}

double ColourModulation::relative_change(const glm::dvec3& position_m,
                                         const glm::dvec3& colour_linear) const {
  double sum = 0.0;
  // band_weight for each band, the colour encoded once (3 powers per texel instead of 6 per
  // tinted band: this runs for every texel of the baked textures).
  std::optional<glm::dvec3> colour_srgb;
  for (const Band& b : bands_) {
    double w = b.params.amplitude;
    if (b.params.tinted) {
      if (!colour_srgb) colour_srgb = clamped_srgb(colour_linear);
      w = tinted_weight(b.params, *colour_srgb, b.tint_srgb);
    }
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
