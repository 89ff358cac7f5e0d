#include "material/skin_pattern.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/constants.h"
#include "base/random.h"
#include "material/cellular_noise.h"

namespace cutaway {

namespace {

/// Purpose tag of the pattern streams in derive_seed paths.
constexpr uint64_t kPurposePattern = 0x7061747465;  // "patte"

double smoothstep(double a, double b, double x) {
  if (!(b > a)) return x < a ? 0.0 : 1.0;
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

/// How much a spot of `radius` covers a point `d` from its centre (a line: `d` from its
/// middle): 1 within (1 - softness) of the radius, 0 beyond it, smoothstep between.
double spot(double d, double radius, double softness) {
  return 1.0 - smoothstep(radius * (1 - softness), radius, d);
}

/// Coverage of a stripe layer: stripes centred at half periods of u = t_section * count +
/// phase + wobble * noise, where the noise is read on a cylinder of one unit per period around
/// (so it wraps with the section) and along the profile at six and twenty-four waves per skin.
double stripe_coverage(const SkinPatternLayer& s, const PerlinNoise& noise, double phase,
                       const glm::dvec2& param) {
  const double angle = 2 * kPi * param.y, radius = s.count / (2 * kPi);
  const glm::dvec3 around(radius * std::cos(angle), radius * std::sin(angle), 0.0);
  const double n = noise(around + glm::dvec3(0, 0, 6 * param.x)) +
                   0.35 * noise(around * 4.0 + glm::dvec3(0, 17.5, 24 * param.x));
  const double u = param.y * s.count + phase + s.wobble * n;
  const double from_centre = std::fabs(u - std::floor(u) - 0.5);
  const double half = 0.5 * s.width, edge = s.softness * half;
  return 1.0 - smoothstep(half - edge, half + edge, from_centre);
}

/// Coverage of a speckle layer: the largest over the lattice points of the 27 cells around the
/// point, each a sphere of radius size (1 + jitter (2h - 1)) about a point placed uniformly in
/// its cell (both from the cell's hash), its edge blended over `softness` of the radius.
double speckle_coverage(const SkinPatternLayer& s, uint64_t cells, const glm::dvec3& position) {
  const glm::dvec3 q = position / s.spacing_m;
  double best = 0;
  visit_feature_points(cells, q, 0, [&](const glm::dvec3& centre, uint64_t& state) {
    const double radius = s.size_m / s.spacing_m * (1 + s.jitter * (2 * cell_uniform(state) - 1));
    const double d = glm::length(q - centre);
    best = std::max(best, spot(d, radius, s.softness));
  });
  return best;
}

/// Coverage of a net layer: the walls between the cells of the lattice points (Worley's cellular
/// basis: the second-nearest point's distance F2 minus the nearest's F1, zero on a wall), lines
/// `size` wide where F2 - F1 < size, their edge blended over `softness`.
double net_coverage(const SkinPatternLayer& s, uint64_t cells, const glm::dvec3& position) {
  const CellDistances d = cell_distances(cells, position / s.spacing_m, 0);
  const double width = s.size_m / s.spacing_m;
  return spot(d.f2 - d.f1, width, s.softness);
}

}  // namespace

SkinPatterns::SkinPatterns(const std::vector<SkinPatternLayer>& layers, uint64_t seed,
                           const DsModel* model) {
  for (size_t k = 0; k < layers.size(); ++k) {
    const uint64_t layer_seed = derive_seed(seed, {kPurposePattern, k});
    uint64_t state = layer_seed;
    const double phase = cell_uniform(state);
    Layer layer{layers[k], PerlinNoise(layer_seed), phase, splitmix64(state), {}, {}};
    if (layer.spec.kind == SkinPatternLayer::Kind::Grains && model) {
      layer.near.cell = layer.spec.size_m;
      for (const DsSurface& s : model->surfaces)
        if (s.role == SurfaceRole::Grain && s.name == layer.spec.grain_set)
          for (const glm::dvec3& site : s.grain_sites) {
            layer.near.add(site, layer.sites.size());
            layer.sites.push_back(site);
          }
    }
    layers_.push_back(std::move(layer));
  }
}

double SkinPatterns::coverage(size_t k, const glm::dvec2& param, const glm::dvec3& position) const {
  const Layer& layer = layers_[k];
  switch (layer.spec.kind) {
    case SkinPatternLayer::Kind::Stripes:
      return stripe_coverage(layer.spec, layer.noise, layer.phase, param);
    case SkinPatternLayer::Kind::Speckles:
      return speckle_coverage(layer.spec, layer.cells, position);
    case SkinPatternLayer::Kind::Net: return net_coverage(layer.spec, layer.cells, position);
    case SkinPatternLayer::Kind::Grains: {
      // The nearest site's spot, its edge blended over `softness` of the radius.
      const SkinPatternLayer& g = layer.spec;
      double best = 0;
      layer.near.visit_near(position, [&](size_t i) {
        const double d = glm::distance(position, layer.sites[i]);
        best = std::max(best, spot(d, g.size_m, g.softness));
        return true;
      });
      return best;
    }
  }
  return 0.0;
}

bool SkinPatterns::has_relief() const {
  return std::any_of(layers_.begin(), layers_.end(),
                     [](const Layer& layer) { return layer.spec.relief_m != 0; });
}

SkinPatterns::Shade SkinPatterns::shade(const glm::dvec2& param, const glm::dvec3& position,
                                        const glm::dvec3& colour) const {
  Shade out{colour, 0.0};
  for (size_t k = 0; k < layers_.size(); ++k) {
    const SkinPatternLayer& spec = layers_[k].spec;
    const double cover = coverage(k, param, position);
    out.colour += (spec.colour - out.colour) * (spec.opacity * cover);
    if (spec.relief_m != 0) out.height += spec.relief_m * cover;
  }
  return out;
}

glm::dvec3 SkinPatterns::operator()(const glm::dvec2& param, const glm::dvec3& position,
                                    const glm::dvec3& colour) const {
  return shade(param, position, colour).colour;
}

}  // namespace cutaway
