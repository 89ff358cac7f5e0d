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
#include "material/cellular_noise.h"
#include "material/texture_field.h"

namespace cutaway {

namespace {

/// The colour clamped to 0..1 and encoded as sRGB, as band_weight compares it.
glm::dvec3 clamped_srgb(const glm::dvec3& colour_linear) {
  return linear_to_srgb(glm::clamp(colour_linear, 0.0, 1.0));
}

/// band_weight of a tinted band, from the colour and the tint already encoded as sRGB.
double tinted_weight(const TextureBand& band, const glm::dvec3& colour_srgb,
                     const glm::dvec3& tint_srgb) {
  const double d = glm::distance(colour_srgb, tint_srgb);
  if (!(d < band.reach)) return 0.0;
  const double q = 1.0 - (d / band.reach) * (d / band.reach);
  return band.amplitude * q * q;
}

/// Purpose tag of the cell lattices in derive_seed paths.
constexpr uint64_t kPurposeCells = 0x63656c6c;  // "cell"

}  // namespace

/// The weight of a band for a colour whose clamped sRGB encoding is computed at most once for
/// all bands (3 powers per texel instead of 6 per tinted band: this runs for every texel of the
/// baked textures).
class BandWeights {
 public:
  explicit BandWeights(const glm::dvec3& colour_linear) : colour_linear_(colour_linear) {}
  double operator()(const TextureBand& band, const glm::dvec3& tint_srgb) {
    if (!band.tinted) return band.amplitude;
    if (!srgb_) srgb_ = clamped_srgb(colour_linear_);
    return tinted_weight(band, *srgb_, tint_srgb);
  }

 private:
  glm::dvec3 colour_linear_;
  std::optional<glm::dvec3> srgb_;
};

double band_weight(const TextureBand& band, const glm::dvec3& colour_linear) {
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
  for (size_t b = 0; b < npr.cell_bands.size(); ++b) {
    const CellBand& c = npr.cell_bands[b];
    cells_.push_back(Cells{c, derive_seed(seed, {kPurposeCells, b}), linear_to_srgb(c.tint)});
  }
}

double ColourModulation::relative_change(const glm::dvec3& position_m,
                                         const glm::dvec3& colour_linear) const {
  BandWeights weight(colour_linear);
  return relative_change(position_m, weight);
}

double ColourModulation::relative_change(const glm::dvec3& position_m, BandWeights& weight) const {
  double sum = 0.0;
  for (const Band& b : bands_) {
    const double w = weight(b.params, b.tint_srgb);
    if (w == 0.0) continue;
    const LatticePoint l = band_lattice_point(b.params, position_m);
    sum +=
        w * (l.period_x ? b.noise.periodic(l.q + b.offset, l.period_x) : b.noise(l.q + b.offset));
  }
  return sum;
}

CellMasks cell_masks(const CellBand& band, uint64_t cells, const glm::dvec3& position_m) {
  const LatticePoint l = band_lattice_point(band, position_m);
  const CellDistances d = cell_distances(cells, l.q, l.period_x);
  CellMasks m;
  // The wall: full within half its width of the bisector (F2 - F1 = 0), fading to 0 at the
  // width (F2 - F1 is about twice the distance to the bisector near it).
  const double gap = d.f2 - d.f1, w = band.wall_width;
  if (w > 0 && gap < w) {
    const double t = std::clamp((gap - 0.5 * w) / (0.5 * w), 0.0, 1.0);
    m.wall = 1.0 - t * t * (3 - 2 * t);
  }
  m.centre = d.f1 + d.f2 > 0 ? std::clamp(1.0 - 2.0 * d.f1 / (d.f1 + d.f2), 0.0, 1.0) : 1.0;
  return m;
}

glm::dvec3 ColourModulation::operator()(const glm::dvec3& position_m,
                                        const glm::dvec3& colour_linear, double strength) const {
  return modulate(position_m, colour_linear, strength, nullptr);
}

glm::dvec3 ColourModulation::operator()(const glm::dvec3& position_m,
                                        const glm::dvec3& colour_linear, double strength,
                                        glm::dvec2& material) const {
  return modulate(position_m, colour_linear, strength, &material);
}

/// operator()'s work; `material`, when given, moved by the cells' roughness.
glm::dvec3 ColourModulation::modulate(const glm::dvec3& position_m, const glm::dvec3& colour_linear,
                                      double strength, glm::dvec2* material) const {
  if (strength == 0.0 || (bands_.empty() && cells_.empty())) return colour_linear;
  BandWeights weight(colour_linear);
  const double factor = 1.0 + strength * relative_change(position_m, weight);
  glm::dvec3 c = glm::clamp(colour_linear * factor, 0.0, 1.0);
  for (const Cells& layer : cells_) {
    const double k = std::min(1.0, strength * weight(layer.params, layer.tint_srgb));
    if (k == 0.0) continue;
    const CellMasks m = cell_masks(layer.params, layer.seed, position_m);
    if (layer.params.has_centre) c += (layer.params.centre - c) * (k * m.centre);
    if (layer.params.has_wall) c += (layer.params.wall - c) * (k * m.wall);
    if (material && layer.params.centre_roughness >= 0)
      material->x += (layer.params.centre_roughness - material->x) * (k * m.centre);
    if (material && layer.params.wall_roughness >= 0)
      material->x += (layer.params.wall_roughness - material->x) * (k * m.wall);
  }
  return c;
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
  if (strength == 0.0 || (npr.perlin_bands.empty() && npr.cell_bands.empty())) return;
  const ColourModulation modulation(npr, seed);
  for (size_t i = 0; i < colour.size(); ++i) {
    colour[i] = modulation(position_m[i], colour[i], strength);
  }
}

void modulate_colours(ShadedMesh& mesh, const NprSettings& npr, double strength, uint64_t seed) {
  modulate_colours(mesh.position, mesh.colour, npr, strength, seed);
}

}  // namespace cutaway
